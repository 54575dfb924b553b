// Smoke test of extension.js under plain node, with a stubbed `vscode`
// module: the real vscode-languageclient loads, `activate` registers the
// commands and starts `<ptsc.path> lsp`, a missing binary is reported, and
// the render/watch command lines survive the shell (they are run by bash
// against a fake ptsc that prints its arguments).
// Run: node test/smoke.js (package.sh runs it before packaging).
'use strict';

const assert = require('assert');
const childProcess = require('child_process');
const fs = require('fs');
const Module = require('module');
const os = require('os');
const path = require('path');

const root = path.join(__dirname, '..');
const manifest = JSON.parse(fs.readFileSync(path.join(root, 'package.json'), 'utf8'));

// A fake ptsc (prints its arguments, one a line) in a folder whose name needs quoting.
const tmp = fs.mkdtempSync(path.join(os.tmpdir(), 'ptsc-smoke-'));
const binDir = path.join(tmp, "bin dir with 'quotes' $HOME");
fs.mkdirSync(binDir);
const fakePtsc = path.join(binDir, 'ptsc');
fs.writeFileSync(fakePtsc, '#!/bin/sh\nfor a in "$@"; do printf "%s\\n" "$a"; done\n', { mode: 0o755 });
const sceneDir = path.join(tmp, 'scenes; rm -rf nothing');
fs.mkdirSync(sceneDir);
const scene = path.join(sceneDir, "it's a \"scene\" `x`.pts");
fs.writeFileSync(scene, 'camera { }\n');

// ---- the vscode stub -------------------------------------------------------
const settings = { 'ptsc.path': fakePtsc, 'ptsc.trace.server': 'off' };
const registered = new Map();
const errors = [];
const terminals = [];
const executed = [];
const configListeners = [];

function disposable() {
  return { dispose() {} };
}
function event(listeners) {
  return (fn) => {
    if (listeners) listeners.push(fn);
    return disposable();
  };
}
class Uri {
  constructor(scheme, fsPath) {
    this.scheme = scheme;
    this.fsPath = fsPath;
    this.path = fsPath;
  }
  static file(p) {
    return new Uri('file', p);
  }
  toString() {
    return `${this.scheme}://${this.fsPath}`;
  }
}
let saved = 0;
const sceneDoc = {
  uri: Uri.file(scene),
  fileName: scene,
  languageId: 'pts',
  isUntitled: false,
  isDirty: true,
  async save() {
    saved += 1;
    this.isDirty = false;
    return true;
  },
};

const vscodeStub = {
  Uri,
  Disposable: class {
    constructor(f) {
      this.dispose = f || (() => {});
    }
    static from(...ds) {
      return { dispose: () => ds.forEach((d) => d.dispose()) };
    }
  },
  EventEmitter: class {
    constructor() {
      this.event = event();
    }
    fire() {}
    dispose() {}
  },
  workspace: {
    workspaceFolders: [{ uri: Uri.file(tmp), name: 'tmp', index: 0 }],
    getConfiguration(section) {
      return {
        get(key, fallback) {
          const v = settings[`${section}.${key}`];
          return v === undefined ? fallback : v;
        },
      };
    },
    getWorkspaceFolder() {
      return vscodeStub.workspace.workspaceFolders[0];
    },
    async openTextDocument(uri) {
      assert.strictEqual(uri.fsPath, scene);
      return sceneDoc;
    },
    createFileSystemWatcher(glob) {
      return { glob, ...disposable() };
    },
    onDidChangeConfiguration: event(configListeners),
  },
  window: {
    activeTextEditor: { document: sceneDoc },
    createOutputChannel(name) {
      return { name, append() {}, appendLine() {}, show() {}, dispose() {} };
    },
    async showErrorMessage(message) {
      errors.push(message);
      return undefined;
    },
    createTerminal(options) {
      const t = { options, name: options.name, exitStatus: undefined, sent: [], shown: 0 };
      t.sendText = (text, addNewLine = true) => t.sent.push({ text, addNewLine });
      t.show = () => (t.shown += 1);
      t.dispose = () => {};
      terminals.push(t);
      return t;
    },
    onDidCloseTerminal: event(),
  },
  commands: {
    registerCommand(id, fn) {
      assert(!registered.has(id), `${id} registered twice`);
      registered.set(id, fn);
      return disposable();
    },
    async executeCommand(...args) {
      executed.push(args);
    },
  },
  env: { shell: '/bin/bash' },
};
// Anything else the language client touches at load time: a harmless object.
const vscodeProxy = new Proxy(vscodeStub, {
  get(target, prop) {
    if (prop in target) return target[prop];
    if (typeof prop === 'symbol' || prop === 'then') return undefined;
    return new Proxy(function stub() {}, { get: (t, p) => (p === 'prototype' ? {} : undefined) });
  },
});

// ---- a recording LanguageClient over the real module ------------------------
const clients = [];
let realClientModule;
const originalLoad = Module._load;
Module._load = function load(request, parent, isMain) {
  if (request === 'vscode') return vscodeProxy;
  if (request === 'vscode-languageclient/node' && parent && parent.filename === path.join(root, 'extension.js')) {
    realClientModule = originalLoad.call(this, request, parent, isMain);
    class RecordingClient {
      constructor(id, name, serverOptions, clientOptions) {
        Object.assign(this, { id, name, serverOptions, clientOptions, started: false, stopped: false });
        clients.push(this);
      }
      async start() {
        this.started = true;
      }
      async stop() {
        this.stopped = true;
      }
    }
    return { ...realClientModule, LanguageClient: RecordingClient };
  }
  return originalLoad.call(this, request, parent, isMain);
};

function shellRun(line) {
  return childProcess.execFileSync('bash', ['-c', line], { encoding: 'utf8' }).split('\n').slice(0, -1);
}

async function main() {
  // The manifest: what VS Code reads.
  assert.strictEqual(manifest.main, './extension.js');
  assert(manifest.activationEvents.includes('onLanguage:pts'));
  assert(fs.existsSync(path.join(root, manifest.contributes.grammars[0].path)));
  assert(fs.existsSync(path.join(root, manifest.contributes.languages[0].configuration)));
  assert.deepStrictEqual(manifest.contributes.languages[0].extensions, ['.pts', '.ptsi']);
  const props = manifest.contributes.configuration.properties;
  assert.strictEqual(props['ptsc.path'].default, 'ptsc');
  assert.deepStrictEqual(props['ptsc.trace.server'].enum, ['off', 'messages', 'verbose']);
  // In an untrusted workspace, its ptsc.path (a program to run) is ignored.
  assert.deepStrictEqual(manifest.capabilities.untrustedWorkspaces.restrictedConfigurations, ['ptsc.path']);
  const clientManifest = require(path.join(root, 'node_modules/vscode-languageclient/package.json'));
  assert.strictEqual(
    manifest.engines.vscode,
    clientManifest.engines.vscode,
    'engines.vscode should be what vscode-languageclient requires',
  );

  // The docs name the .vsix this version makes (not checked in the unpacked .vsix).
  for (const doc of ['../README.md', '../../README.md']) {
    const file = path.join(root, doc);
    if (fs.existsSync(path.join(root, 'package.sh')) && fs.existsSync(file)) {
      const vsix = `ptsc-pts-${manifest.version}.vsix`;
      assert(fs.readFileSync(file, 'utf8').includes(vsix), `${path.normalize(file)} should name ${vsix}`);
    }
  }

  const ext = require(path.join(root, 'extension.js'));
  assert(realClientModule && typeof realClientModule.LanguageClient === 'function', 'the real client did not load');
  assert.strictEqual(typeof ext.activate, 'function');
  assert.strictEqual(typeof ext.deactivate, 'function');

  const context = { subscriptions: [] };
  await ext.activate(context);

  // Every contributed command is registered, and nothing else.
  const contributed = manifest.contributes.commands.map((c) => c.command).sort();
  assert.deepStrictEqual([...registered.keys()].sort(), contributed);
  assert.deepStrictEqual(contributed, ['ptsc.render', 'ptsc.restartServer', 'ptsc.watch']);
  assert(context.subscriptions.length >= contributed.length);

  // The server: `<ptsc.path> lsp` over stdio, for pts documents.
  assert.strictEqual(clients.length, 1);
  const c = clients[0];
  assert.strictEqual(c.id, 'ptsc', 'the id is the settings section of ptsc.trace.server');
  assert(c.started);
  assert.strictEqual(c.serverOptions.run.command, fakePtsc);
  assert.deepStrictEqual(c.serverOptions.run.args, ['lsp']);
  assert.strictEqual(c.serverOptions.run.transport, realClientModule.TransportKind.stdio);
  assert(c.clientOptions.documentSelector.every((s) => s.language === 'pts'));
  assert(c.clientOptions.documentSelector.some((s) => s.scheme === 'file'));
  assert.strictEqual(c.clientOptions.synchronize.fileEvents.glob, '**/*.{pts,ptsi}');
  assert.deepStrictEqual(errors, []);

  // Render: saves the scene, one terminal named ptsc, a command line bash reads back.
  await registered.get('ptsc.render')();
  assert.strictEqual(saved, 1);
  assert.strictEqual(terminals.length, 1);
  const term = terminals[0];
  assert.strictEqual(term.name, 'ptsc');
  assert.strictEqual(term.options.cwd, tmp);
  assert.strictEqual(term.sent.length, 1);
  assert.deepStrictEqual(shellRun(term.sent[0].text), ['render', scene]);

  // Watch from the explorer (a Uri argument): the same terminal.
  await registered.get('ptsc.watch')(Uri.file(scene));
  assert.strictEqual(terminals.length, 1, 'the terminal is reused');
  assert.deepStrictEqual(shellRun(term.sent[1].text), ['watch', scene]);
  // Render again: the running watch is stopped (Ctrl-C) first.
  await registered.get('ptsc.render')();
  assert.deepStrictEqual(term.sent[2], { text: '\u0003', addNewLine: false });
  assert.deepStrictEqual(shellRun(term.sent[3].text), ['render', scene]);
  assert.strictEqual(saved, 1, 'a saved scene is not saved again');

  // The other shells' quoting.
  const q = ext._test.quoteForShell;
  assert.strictEqual(q("a'b", 'C:\\Windows\\System32\\WindowsPowerShell\\v1.0\\powershell.exe'), "'a''b'");
  assert.strictEqual(q('C:\\a b\\s.pts', 'C:\\Windows\\System32\\cmd.exe'), '"C:\\a b\\s.pts"');
  assert.strictEqual(q("a'b\\c", '/usr/bin/fish'), "'a\\'b\\\\c'");
  assert.strictEqual(ext._test.commandLine('C:\\p\\ptsc.exe', 'render', 'x.pts', 'pwsh.exe'), "& 'C:\\p\\ptsc.exe' render 'x.pts'");

  // A bare name is looked up on PATH.
  const found = ext._test.findPtsc('ptsc', { PATH: ['/nonexistent', binDir].join(path.delimiter) });
  assert.strictEqual(found, fakePtsc);
  assert.strictEqual(ext._test.findPtsc('ptsc', { PATH: '/nonexistent' }), undefined);
  // ~ and ${workspaceFolder} are expanded.
  settings['ptsc.path'] = '${workspaceFolder}/target/release/ptsc';
  assert.strictEqual(ext._test.configuredPath(), `${tmp}/target/release/ptsc`);
  settings['ptsc.path'] = '~/bin/ptsc';
  assert.strictEqual(ext._test.configuredPath(), path.join(os.homedir(), 'bin/ptsc'));

  // A missing binary: the old client stops, no new one, a message naming ptsc.path.
  settings['ptsc.path'] = path.join(tmp, 'no-such-ptsc');
  configListeners.forEach((f) => f({ affectsConfiguration: (s) => s === 'ptsc.path' }));
  await new Promise((r) => setTimeout(r, 10));
  assert(c.stopped);
  assert.strictEqual(clients.length, 1);
  assert.strictEqual(errors.length, 1);
  assert(errors[0].includes('ptsc.path'), errors[0]);
  // Render with no binary: a message too, nothing sent.
  await registered.get('ptsc.render')();
  assert.strictEqual(errors.length, 2);
  assert.strictEqual(term.sent.length, 4);

  // Back to a binary found on PATH: the restart command starts a new client.
  settings['ptsc.path'] = 'ptsc';
  process.env.PATH = `${binDir}${path.delimiter}${process.env.PATH}`;
  await registered.get('ptsc.restartServer')();
  assert.strictEqual(clients.length, 2);
  assert.strictEqual(clients[1].serverOptions.run.command, fakePtsc);
  assert.strictEqual(clients[1].clientOptions.synchronize.fileEvents, c.clientOptions.synchronize.fileEvents);
  await ext.deactivate();
  assert(clients[1].stopped);

  fs.rmSync(tmp, { recursive: true, force: true });
  console.log('smoke: ok (activate, 3 commands, server options, missing binary, shell quoting)');
}

main().catch((err) => {
  console.error(err);
  process.exit(1);
});
