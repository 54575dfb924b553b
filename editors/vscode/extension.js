// The ptsc extension: starts the language server (`ptsc lsp`) for `.pts`
// scenes and `.ptsi` include fragments, and runs `ptsc render` / `ptsc watch`
// in a terminal. Plain JavaScript: no build step (package.sh packs it as is).
'use strict';

const fs = require('fs');
const os = require('os');
const path = require('path');
const vscode = require('vscode');
const { LanguageClient, TransportKind } = require('vscode-languageclient/node');

const CLIENT_ID = 'ptsc'; // also the settings' section: ptsc.trace.server
const TERMINAL_NAME = 'ptsc';

/** @type {LanguageClient | undefined} */
let client;
/** @type {vscode.Terminal | undefined} */
let terminal;
/** Whether the terminal's last command was a watch (still running, then). */
let terminalWatching = false;
/** @type {vscode.OutputChannel | undefined} */
let output;
/** @type {vscode.FileSystemWatcher | undefined} */
let watcher;

/** The `ptsc.path` setting, with `~` and `${workspaceFolder}` expanded. */
function configuredPath() {
  let p = vscode.workspace.getConfiguration('ptsc').get('path', 'ptsc');
  p = typeof p === 'string' && p.trim() !== '' ? p.trim() : 'ptsc';
  if (p === '~' || p.startsWith('~/') || p.startsWith('~\\')) {
    p = path.join(os.homedir(), p.slice(1));
  }
  const folders = vscode.workspace.workspaceFolders;
  if (p.includes('${workspaceFolder}') && folders && folders.length > 0) {
    p = p.split('${workspaceFolder}').join(folders[0].uri.fsPath);
  }
  return p;
}

function isExecutableFile(file) {
  try {
    if (!fs.statSync(file).isFile()) return false;
    if (process.platform !== 'win32') fs.accessSync(file, fs.constants.X_OK);
    return true;
  } catch {
    return false;
  }
}

/**
 * The binary to run: the configured path if it names a file, or the first
 * match on PATH for a bare name. Undefined when there is none.
 */
function findPtsc(configured, env = process.env, platform = process.platform) {
  const exts =
    platform === 'win32'
      ? ['', ...(env.PATHEXT || '.EXE;.CMD;.BAT;.COM').split(';').filter(Boolean)]
      : [''];
  const hasSeparator = configured.includes('/') || (platform === 'win32' && configured.includes('\\'));
  if (hasSeparator || path.isAbsolute(configured)) {
    for (const ext of exts) {
      if (isExecutableFile(configured + ext)) return configured + ext;
    }
    return undefined;
  }
  const dirs = (env.PATH || env.Path || '').split(path.delimiter).filter(Boolean);
  for (const dir of dirs) {
    for (const ext of exts) {
      const candidate = path.join(dir, configured + ext);
      if (isExecutableFile(candidate)) return candidate;
    }
  }
  return undefined;
}

/** Says the binary is missing, and how to fix it; offers the setting. */
async function reportMissing(configured) {
  const message =
    configured.includes('/') || configured.includes('\\')
      ? `ptsc: the binary "${configured}" (setting ptsc.path) does not exist or is not executable. ` +
        'Set "ptsc.path" to the full path of ptsc (e.g. /home/you/ptsc/target/release/ptsc).'
      : `ptsc: "${configured}" was not found on PATH, so the language server (ptsc lsp) cannot start. ` +
        'Install it (cargo install --path . in the ptsc checkout) or set "ptsc.path" to the full path of the binary.';
  const openSettings = 'Open the ptsc.path setting';
  const choice = await vscode.window.showErrorMessage(message, openSettings);
  if (choice === openSettings) {
    await vscode.commands.executeCommand('workbench.action.openSettings', 'ptsc.path');
  }
}

/** What starts the server: `<ptsc> lsp` over stdio. */
function serverOptions(executable) {
  const run = { command: executable, args: ['lsp'], transport: TransportKind.stdio };
  return { run, debug: run };
}

function clientOptions() {
  return {
    documentSelector: [
      { scheme: 'file', language: 'pts' },
      { scheme: 'untitled', language: 'pts' },
    ],
    outputChannel: output,
    // Included fragments change on disk (other programs, git): tell the server.
    synchronize: { fileEvents: watcher },
  };
}

async function startClient() {
  const configured = configuredPath();
  const executable = findPtsc(configured);
  if (!executable) {
    void reportMissing(configured);
    return undefined;
  }
  const c = new LanguageClient(CLIENT_ID, 'ptsc language server', serverOptions(executable), clientOptions());
  client = c;
  try {
    await c.start();
  } catch (err) {
    const detail = err && err.message ? err.message : String(err);
    void vscode.window.showErrorMessage(
      `ptsc: the language server (${executable} lsp) did not start: ${detail}. ` +
        'An older ptsc has no "lsp" command; set "ptsc.path" to a newer binary.',
    );
  }
  return c;
}

async function stopClient() {
  const c = client;
  client = undefined;
  if (c) {
    try {
      await c.stop();
    } catch {
      // A server that never started cannot be stopped: nothing to do.
    }
  }
}

async function restartClient() {
  await stopClient();
  await startClient();
}

/** `bash`, `pwsh`, `cmd` …: the shell's name from its path (Windows paths too). */
function shellName(shellPath) {
  const base = (shellPath || '').split(/[\\/]/).pop();
  return base.toLowerCase().replace(/\.exe$/, '');
}

/** Quotes `arg` for the shell at `shellPath` (the terminal's shell). */
function quoteForShell(arg, shellPath) {
  const shell = shellName(shellPath);
  if (shell === 'cmd') {
    // Windows file names cannot contain a double quote.
    return `"${arg}"`;
  }
  if (shell === 'powershell' || shell === 'pwsh') {
    return `'${arg.replace(/'/g, "''")}'`;
  }
  if (shell === 'fish') {
    return `'${arg.replace(/\\/g, '\\\\').replace(/'/g, "\\'")}'`;
  }
  // sh, bash, zsh, dash, ksh …: nothing is special inside single quotes.
  return `'${arg.replace(/'/g, "'\\''")}'`;
}

/** The command line for `ptsc <sub> FILE` in the given shell. */
function commandLine(executable, sub, file, shellPath) {
  const shell = shellName(shellPath);
  const exe = quoteForShell(executable, shellPath);
  // PowerShell runs a quoted program only with the call operator.
  const prefix = shell === 'powershell' || shell === 'pwsh' ? '& ' : '';
  return `${prefix}${exe} ${sub} ${quoteForShell(file, shellPath)}`;
}

/** The scene to run: the command's argument (explorer, title bar) or the active editor's. */
async function sceneDocument(uri) {
  if (uri instanceof vscode.Uri) {
    return vscode.workspace.openTextDocument(uri);
  }
  const editor = vscode.window.activeTextEditor;
  return editor ? editor.document : undefined;
}

async function runInTerminal(sub, uri) {
  const doc = await sceneDocument(uri);
  if (!doc || doc.languageId !== 'pts') {
    void vscode.window.showErrorMessage(`ptsc: open a .pts scene to ${sub} it.`);
    return;
  }
  if (doc.isUntitled || doc.uri.scheme !== 'file') {
    void vscode.window.showErrorMessage(`ptsc: save the scene to a file before you ${sub} it.`);
    return;
  }
  if (doc.isDirty && !(await doc.save())) {
    void vscode.window.showErrorMessage(`ptsc: ${doc.fileName} could not be saved.`);
    return;
  }
  const configured = configuredPath();
  const executable = findPtsc(configured);
  if (!executable) {
    void reportMissing(configured);
    return;
  }
  if (!terminal || terminal.exitStatus !== undefined) {
    const folder = vscode.workspace.getWorkspaceFolder(doc.uri);
    terminal = vscode.window.createTerminal({
      name: TERMINAL_NAME,
      cwd: folder ? folder.uri.fsPath : path.dirname(doc.fileName),
    });
    terminalWatching = false;
  } else if (terminalWatching) {
    // Stop the watch running there first (Ctrl-C).
    terminal.sendText('\u0003', false);
  }
  terminal.show(true);
  terminal.sendText(commandLine(executable, sub, doc.fileName, vscode.env.shell));
  terminalWatching = sub === 'watch';
}

async function activate(context) {
  output = vscode.window.createOutputChannel('ptsc language server');
  watcher = vscode.workspace.createFileSystemWatcher('**/*.{pts,ptsi}');
  context.subscriptions.push(
    output,
    watcher,
    vscode.commands.registerCommand('ptsc.render', (uri) => runInTerminal('render', uri)),
    vscode.commands.registerCommand('ptsc.watch', (uri) => runInTerminal('watch', uri)),
    vscode.commands.registerCommand('ptsc.restartServer', restartClient),
    vscode.window.onDidCloseTerminal((t) => {
      if (t === terminal) {
        terminal = undefined;
        terminalWatching = false;
      }
    }),
    vscode.workspace.onDidChangeConfiguration((e) => {
      if (e.affectsConfiguration('ptsc.path')) void restartClient();
    }),
  );
  await startClient();
}

function deactivate() {
  return stopClient();
}

module.exports = {
  activate,
  deactivate,
  // For test/smoke.js.
  _test: { findPtsc, quoteForShell, commandLine, configuredPath, serverOptions },
};
