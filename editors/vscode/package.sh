#!/usr/bin/env bash
# Builds the VS Code extension: editors/vscode/ptsc-pts-<version>.vsix.
# npm ci (the locked dependencies), the smoke test (test/smoke.js), with
# PTSC_BIN a handshake with the real server (test/handshake.js), then
# vsce package with the runtime dependencies (vscode-languageclient), and a
# check that the .vsix holds what VS Code needs. Needs node >= 18 and npm.
set -euo pipefail
cd "$(dirname "$0")"

version=$(node -p "require('./package.json').version")
out="ptsc-pts-$version.vsix"

# No install scripts: nothing here needs building, and vsce's optional
# keytar (a native module, only for publishing) would try to.
npm ci --ignore-scripts --no-audit --no-fund --prefer-offline --loglevel=error
node test/smoke.js
# With PTSC_BIN (a ptsc binary; CI passes the one its tests built), the
# client library against the real server: initialize, a scene's diagnostics,
# shutdown (test/handshake.js). Skipped for a ptsc without the lsp command.
if [ -n "${PTSC_BIN:-}" ]; then
  if "$PTSC_BIN" help lsp >/dev/null 2>&1; then
    node test/handshake.js "$PTSC_BIN"
  else
    echo "package.sh: skipping the server handshake: $PTSC_BIN has no lsp command"
  fi
fi

rm -f "$out"
# Non-interactive: the licence is the project's (package.json's "license";
# there is no LICENSE file to copy) and the project has no public repository
# URL yet; stdin is closed so that any other question fails instead of waiting.
npx --no-install vsce package --out "$out" --skip-license --allow-missing-repository </dev/null

# The .vsix must hold the extension, its manifest, the grammar and the
# language client (with its own dependencies), and no tests or tools.
if command -v unzip >/dev/null 2>&1; then
  listing=$(unzip -Z1 "$out")
else
  listing=$(python3 -c 'import sys, zipfile; print("\n".join(zipfile.ZipFile(sys.argv[1]).namelist()))' "$out")
fi
for f in extension/extension.js extension/package.json extension/language-configuration.json \
  extension/syntaxes/pts.tmLanguage.json \
  extension/node_modules/vscode-languageclient/node.js \
  extension/node_modules/vscode-languageclient/lib/node/main.js \
  extension/node_modules/vscode-languageserver-protocol/package.json \
  extension/node_modules/vscode-jsonrpc/package.json; do
  if ! grep -qxF "$f" <<< "$listing"; then
    echo "package.sh: $out lacks $f" >&2
    exit 1
  fi
done
if grep -E '^extension/(test/|package\.sh|node_modules/@vscode/vsce/)' <<< "$listing"; then
  echo "package.sh: $out holds files it should not (above)" >&2
  exit 1
fi
# The packed extension runs: the smoke test again, on the unpacked .vsix
# (its own node_modules only, so a dependency left out fails here).
unpacked=$(mktemp -d)
trap 'rm -rf "$unpacked"' EXIT
if command -v unzip >/dev/null 2>&1; then
  unzip -q "$out" -d "$unpacked"
else
  python3 -c 'import sys, zipfile; zipfile.ZipFile(sys.argv[1]).extractall(sys.argv[2])' "$out" "$unpacked"
fi
mkdir "$unpacked/extension/test"
cp test/smoke.js "$unpacked/extension/test/"
node "$unpacked/extension/test/smoke.js"
echo "package.sh: built editors/vscode/$out ($(wc -c < "$out") bytes, $(wc -l <<< "$listing") files)"
