#!/usr/bin/env python3
"""Latency of `ptsc lsp` as an editor sees it (issue 38's figures).

Usage: python3 scripts/lsp_latency.py [PTSC] [RUNS]
PTSC defaults to target/release/ptsc. Prints the median and the worst of
RUNS (default 5) sessions of:
  open     didOpen of examples/bench/cornell.pts -> its first publishDiagnostics
  edit     an edit (incremental, as VS Code sends) to a 100,000-sphere scene
           (11 MB, generated) -> the publishDiagnostics of the new version
  hover    hover on examples/bench/cornell.pts while the large scene is re-checked
  complete completion on examples/bench/cornell.pts, same
A benchmark, not a test: run it on an idle machine
(python3 ../shared/bench/cpuload.py wait) and keep the figures in the notes.
"""
import json, os, random, statistics, subprocess, sys, tempfile, threading, time, queue

here = os.path.dirname(os.path.abspath(__file__))
root = os.path.dirname(here)
ptsc = sys.argv[1] if len(sys.argv) > 1 else os.path.join(root, "target", "release", "ptsc")
runs = int(sys.argv[2]) if len(sys.argv) > 2 else 5


class Client:
    def __init__(self):
        self.p = subprocess.Popen([ptsc, "lsp"], stdin=subprocess.PIPE, stdout=subprocess.PIPE)
        self.q = queue.Queue()
        threading.Thread(target=self.read, daemon=True).start()
        self.id = 0

    def read(self):
        while True:
            n = None
            while True:
                line = self.p.stdout.readline()
                if not line:
                    return
                if line == b"\r\n":
                    break
                if line.lower().startswith(b"content-length"):
                    n = int(line.split(b":")[1])
            self.q.put((time.perf_counter(), json.loads(self.p.stdout.read(n))))

    def send(self, obj):
        obj["jsonrpc"] = "2.0"
        b = json.dumps(obj).encode()
        self.p.stdin.write(b"Content-Length: %d\r\n\r\n" % len(b) + b)
        self.p.stdin.flush()
        return time.perf_counter()

    def request(self, method, params):
        self.id += 1
        t = self.send({"id": self.id, "method": method, "params": params})
        return t, self.wait(lambda m: m.get("id") == self.id)

    def wait(self, pred):
        while True:
            t, m = self.q.get(timeout=60)
            if pred(m):
                return t, m

    def close(self):
        self.request("shutdown", None)
        self.send({"method": "exit"})
        self.p.wait(timeout=10)


def diagnostics_of(uri, version):
    return lambda m: m.get("method") == "textDocument/publishDiagnostics" and m["params"]["uri"] == uri and m["params"].get("version") == version


def session(big_text, big_path):
    c = Client()
    c.request("initialize", {"capabilities": {}})
    c.send({"method": "initialized", "params": {}})
    cornell = os.path.join(root, "examples", "bench", "cornell.pts")
    uri = "file://" + cornell
    text = open(cornell).read()
    t0 = c.send({"method": "textDocument/didOpen", "params": {"textDocument": {"uri": uri, "languageId": "pts", "version": 1, "text": text}}})
    t1, _ = c.wait(diagnostics_of(uri, 1))
    big_uri = "file://" + big_path
    c.send({"method": "textDocument/didOpen", "params": {"textDocument": {"uri": big_uri, "languageId": "pts", "version": 1, "text": big_text}}})
    c.wait(diagnostics_of(big_uri, 1))
    # An edit in the middle: a radius changed.
    line = 50_000
    t2 = c.send({"method": "textDocument/didChange", "params": {"textDocument": {"uri": big_uri, "version": 2}, "contentChanges": [
        {"range": {"start": {"line": line, "character": 0}, "end": {"line": line, "character": 0}}, "text": "sphere { radius 0.3 }\n"}]}})
    # While it is re-checked: hover and completion on cornell.
    word = text.index("radius")
    before = text[:word]
    pos = {"line": before.count("\n"), "character": len(before) - (before.rfind("\n") + 1) + 1}
    th0, (th1, _) = c.request("textDocument/hover", {"textDocument": {"uri": uri}, "position": pos})
    tc0, (tc1, _) = c.request("textDocument/completion", {"textDocument": {"uri": uri}, "position": pos})
    t3, _ = c.wait(diagnostics_of(big_uri, 2))
    c.close()
    return {"open": t1 - t0, "edit": t3 - t2, "hover": th1 - th0, "complete": tc1 - tc0}


def main():
    rng = random.Random(1)
    lines = ["camera { position <13, 2, 3> look_at <0, 0, 0> fov 30 }", "background rgb <0.7, 0.8, 1.0>"]
    for _ in range(100_000):
        c = [rng.uniform(-10, 10) for _ in range(3)]
        d = [rng.random() for _ in range(3)]
        lines.append("sphere { center <%f, %f, %f> radius 0.2 material { diffuse rgb <%f, %f, %f> } }" % (*c, *d))
    big_text = "\n".join(lines) + "\n"
    with tempfile.TemporaryDirectory() as d:
        big_path = os.path.join(d, "spheres100k.pts")
        open(big_path, "w").write(big_text)
        results = [session(big_text, big_path) for _ in range(runs)]
    print("%d MB scene, %d sessions" % (len(big_text) >> 20, runs))
    for k in ["open", "edit", "hover", "complete"]:
        xs = [r[k] * 1000 for r in results]
        print("%-9s median %7.1f ms   worst %7.1f ms" % (k, statistics.median(xs), max(xs)))


main()
