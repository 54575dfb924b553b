// The extension's client library against a real server: starts `<ptsc> lsp`
// (as the extension does), initializes, opens a scene with a mistake, waits
// for its diagnostics (pushed, or pulled when the server offers pulling),
// then shuts the server down and checks that it exits.
// Run: node test/handshake.js PATH/TO/ptsc (package.sh runs it with $PTSC_BIN).
'use strict';

const assert = require('assert');
const childProcess = require('child_process');
const fs = require('fs');
const os = require('os');
const path = require('path');
const { pathToFileURL } = require('url');
const lsp = require('vscode-languageserver-protocol/node');

const ptsc = process.argv[2];
if (!ptsc) {
  console.error('usage: node test/handshake.js PATH/TO/ptsc');
  process.exit(2);
}

function within(ms, promise, what) {
  let timer;
  const timeout = new Promise((_, reject) => {
    timer = setTimeout(() => reject(new Error(`no ${what} within ${ms / 1000} s`)), ms);
  });
  return Promise.race([promise, timeout]).finally(() => clearTimeout(timer));
}

async function main() {
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'ptsc-handshake-'));
  const file = path.join(dir, 'scene.pts');
  // The README's example mistake: `radus` for `radius`.
  const text = 'sphere { center <0, 0, 0> radus 1 }\n';
  fs.writeFileSync(file, text);
  const uri = pathToFileURL(file).href;

  const server = childProcess.spawn(ptsc, ['lsp'], { stdio: ['pipe', 'pipe', 'inherit'] });
  const exited = new Promise((resolve) => server.on('exit', (code, signal) => resolve({ code, signal })));
  const connection = lsp.createProtocolConnection(
    new lsp.StreamMessageReader(server.stdout),
    new lsp.StreamMessageWriter(server.stdin),
  );
  const pushed = new Promise((resolve) => {
    connection.onNotification(lsp.PublishDiagnosticsNotification.type, (params) => {
      if (params.uri === uri && params.diagnostics.length > 0) resolve(params.diagnostics);
    });
  });
  connection.listen();

  const init = await within(
    10000,
    connection.sendRequest(lsp.InitializeRequest.type, {
      processId: process.pid,
      clientInfo: { name: 'ptsc handshake test' },
      rootUri: pathToFileURL(dir).href,
      workspaceFolders: [{ uri: pathToFileURL(dir).href, name: 'scenes' }],
      capabilities: {
        textDocument: {
          publishDiagnostics: { relatedInformation: true },
          diagnostic: { dynamicRegistration: false },
          synchronization: { dynamicRegistration: false },
        },
      },
    }),
    'initialize result',
  );
  assert(init && typeof init.capabilities === 'object', 'initialize returned no capabilities');
  const caps = init.capabilities;
  await connection.sendNotification(lsp.InitializedNotification.type, {});
  await connection.sendNotification(lsp.DidOpenTextDocumentNotification.type, {
    textDocument: { uri, languageId: 'pts', version: 1, text },
  });

  let diagnostics;
  if (caps.diagnosticProvider) {
    const report = await within(
      10000,
      connection.sendRequest(lsp.DocumentDiagnosticRequest.type, { textDocument: { uri } }),
      'diagnostic report',
    );
    diagnostics = report.items;
  } else {
    diagnostics = await within(10000, pushed, 'published diagnostics for the scene');
  }
  assert(diagnostics.length > 0, 'no diagnostic for `radus`');
  assert(
    diagnostics.some((d) => d.range.start.line === 0 && /radus/.test(d.message)),
    `no diagnostic about radus on line 1: ${JSON.stringify(diagnostics)}`,
  );

  await within(10000, connection.sendRequest(lsp.ShutdownRequest.type), 'shutdown reply');
  await connection.sendNotification(lsp.ExitNotification.type);
  const { code, signal } = await within(5000, exited, 'exit after shutdown');
  assert.strictEqual(code, 0, `the server exited with ${code} (${signal})`);
  connection.dispose();
  fs.rmSync(dir, { recursive: true, force: true });
  const offered = Object.keys(caps).filter((k) => caps[k]).sort();
  console.log(`handshake: ok (${ptsc} lsp: ${diagnostics.length} diagnostic(s); offers ${offered.join(', ')})`);
}

main().catch((err) => {
  console.error(`handshake: ${err && err.stack ? err.stack : err}`);
  process.exit(1);
});
