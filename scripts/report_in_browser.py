#!/usr/bin/python3
"""Opens a sweep report page in headless Chromium (Debian's `chromium`) over its DevTools protocol
(python3-websocket) and checks it as a user would see it:
  - it loads with no console error and no uncaught exception,
  - the episode table filters: by the first outcome other than `sorted` the page offers, it shows the
    episodes its data has with that outcome, each saying it; by an axis value no episode has, none;
  - every failure's clip element has a source the browser can play (its metadata loads),
and saves a screenshot of the whole page. Run by Debian's /usr/bin/python3, where setup.sh installs
python3-websocket (another python3 first on the PATH may not have it). Prints one JSON line of what it found (the load time in ms
among it); exit code 0 when every check passed, 1 when one failed, 2 for bad arguments.

  scripts/report_in_browser.py out/sweeps/clutter_100/report/index.html --screenshot out/report.png
"""
import argparse
import base64
import json
import os
import queue
import re
import shutil
import subprocess
import sys
import tempfile
import threading
import time
import urllib.request

import websocket  # python3-websocket


class Page:
    """One page target of a Chromium started for this check, spoken to over CDP."""

    def __init__(self, chromium, timeout_s):
        self.profile = tempfile.mkdtemp(prefix="sortcell_chromium_")
        self.proc = subprocess.Popen(
            [chromium, "--headless=new", "--no-sandbox", "--disable-gpu", "--no-first-run",
             "--allow-file-access-from-files", "--autoplay-policy=no-user-gesture-required",
             "--remote-debugging-port=0", "--user-data-dir=" + self.profile, "--window-size=1280,900",
             "about:blank"],
            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        # Chromium's stderr is read to its end by a thread of its own (a full pipe would stop it), and
        # its lines handed over until the one that gives the DevTools port.
        lines = queue.Queue()
        threading.Thread(target=lambda: [lines.put(l) for l in self.proc.stderr], daemon=True).start()
        port = None
        deadline = time.time() + timeout_s
        while time.time() < deadline and port is None:
            try:
                line = lines.get(timeout=max(0.1, deadline - time.time()))
            except queue.Empty:
                break
            m = re.search(r"DevTools listening on ws://[^:]+:(\d+)/", line)
            if m:
                port = int(m.group(1))
        if port is None:
            self.close()
            raise RuntimeError("chromium did not start (is Debian's chromium installed?)")
        targets = json.load(urllib.request.urlopen("http://127.0.0.1:%d/json/list" % port, timeout=timeout_s))
        page = next(t for t in targets if t["type"] == "page")
        self.ws = websocket.create_connection(page["webSocketDebuggerUrl"], timeout=timeout_s)
        self.next_id = 0
        self.events = []

    def call(self, method, **params):
        self.next_id += 1
        self.ws.send(json.dumps({"id": self.next_id, "method": method, "params": params}))
        while True:
            message = json.loads(self.ws.recv())
            if message.get("id") == self.next_id:
                if "error" in message:
                    raise RuntimeError("%s: %s" % (method, message["error"]))
                return message.get("result", {})
            self.events.append(message)

    def wait_for(self, method, timeout_s):
        deadline = time.time() + timeout_s
        while time.time() < deadline:
            if any(e.get("method") == method for e in self.events):
                return True
            self.ws.settimeout(max(0.1, deadline - time.time()))
            try:
                self.events.append(json.loads(self.ws.recv()))
            except websocket.WebSocketTimeoutException:
                break
        return any(e.get("method") == method for e in self.events)

    def evaluate(self, expression):
        result = self.call("Runtime.evaluate", expression=expression, returnByValue=True, awaitPromise=True)
        if "exceptionDetails" in result:
            raise RuntimeError("page script failed: %s" % result["exceptionDetails"].get("text"))
        return result["result"].get("value")

    def errors(self):
        found = []
        for e in self.events:
            method, params = e.get("method"), e.get("params", {})
            if method == "Runtime.exceptionThrown":
                found.append("exception: " + params["exceptionDetails"].get("text", ""))
            elif method == "Runtime.consoleAPICalled" and params.get("type") in ("error", "assert"):
                found.append("console.error: " + " ".join(str(a.get("value", a.get("description", "")))
                                                          for a in params.get("args", [])))
            elif method == "Log.entryAdded" and params["entry"].get("level") == "error":
                found.append("log: " + params["entry"].get("text", "") + " " + params["entry"].get("url", ""))
        return found

    def close(self):
        if getattr(self, "ws", None):
            self.ws.close()
        self.proc.kill()
        self.proc.wait()
        shutil.rmtree(self.profile, ignore_errors=True)


FILTER_CHECK = """(() => {
  const rows = () => [...document.querySelectorAll('#episodes tbody tr')];
  const total = rows().length;
  const select = document.getElementById('filter-outcome');
  const outcome = [...select.options].map(o => o.value).find(v => v && v !== 'sorted') || 'sorted';
  select.value = outcome;
  select.dispatchEvent(new Event('input'));
  const shown = rows().length;
  const expected = data.episodes.filter(e => e.items.some(i => i[1] === outcome)).length;
  const every = rows().every(r => r.textContent.includes(outcome) || outcome === 'sorted');
  select.value = '';
  const box = document.getElementById('filter-axis');
  box.value = '=no such value';
  box.dispatchEvent(new Event('input'));
  const none = rows().length;
  box.value = '';
  box.dispatchEvent(new Event('input'));
  return {total, outcome, shown, expected, every, none, restored: rows().length};
})()"""

CLIP_CHECK = """(async () => {
  const clips = [...document.querySelectorAll('video.clip')];
  const results = [];
  for (const v of clips) {
    const playable = v.canPlayType('video/mp4; codecs="avc1.64001f"') !== '';
    const loaded = await new Promise(done => {
      if (v.readyState >= 1) return done(true);
      v.addEventListener('loadedmetadata', () => done(true), {once: true});
      v.addEventListener('error', () => done(false), {once: true});
      v.load();
      setTimeout(() => done(v.readyState >= 1), 10000);
    });
    results.push({src: v.getAttribute('src'), playable, loaded, duration: v.duration});
  }
  return results;
})()"""


def save_screenshot(page, box, path):
    shot = page.call("Page.captureScreenshot", format="png", captureBeyondViewport=True, clip=dict(box, scale=1))
    with open(path, "wb") as f:
        f.write(base64.b64decode(shot["data"]))


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("page", help="a report's index.html")
    parser.add_argument("--screenshot", help="PNG of the whole page")
    parser.add_argument("--failure-screenshot", help="PNG of the first failure shown with its still")
    parser.add_argument("--height", type=int, default=0, help="cut --screenshot to this many pixels (0: all)")
    parser.add_argument("--chromium", default=shutil.which("chromium") or "chromium")
    parser.add_argument("--timeout", type=float, default=60.0, help="seconds for each step")
    args = parser.parse_args()
    if not os.path.isfile(args.page):
        print("report_in_browser: error: '%s' is not a file" % args.page, file=sys.stderr)
        return 2

    page = Page(args.chromium, args.timeout)
    try:
        for domain in ("Page", "Runtime", "Log"):
            page.call(domain + ".enable")
        page.call("Page.navigate", url="file://" + os.path.abspath(args.page))
        loaded = page.wait_for("Page.loadEventFired", args.timeout)
        load_ms = page.evaluate("performance.timing.loadEventEnd - performance.timing.navigationStart")
        found = {"page": args.page, "loaded": loaded, "load_ms": load_ms,
                 "page_bytes": os.path.getsize(args.page),
                 "episode_rows": page.evaluate("document.querySelectorAll('#episodes tbody tr').length"),
                 "plots": page.evaluate("document.querySelectorAll('#plots canvas').length"),
                 "filter": page.evaluate(FILTER_CHECK), "clips": page.evaluate(CLIP_CHECK)}
        if args.screenshot:
            size = page.evaluate("({w: document.documentElement.scrollWidth, h: document.documentElement.scrollHeight})")
            height = min(size["h"], args.height) if args.height > 0 else size["h"]
            save_screenshot(page, {"x": 0, "y": 0, "width": size["w"], "height": height}, args.screenshot)
            found["screenshot"] = args.screenshot
        if args.failure_screenshot:
            box = page.evaluate("""(() => {
              const f = [...document.querySelectorAll('.failure')].find(d => d.querySelector('img.still'));
              if (!f) return null;
              const r = f.getBoundingClientRect();
              return {x: r.x + window.scrollX, y: r.y + window.scrollY, width: r.width, height: r.height};
            })()""")
            if box:
                save_screenshot(page, box, args.failure_screenshot)
                found["failure_screenshot"] = args.failure_screenshot
        found["errors"] = page.errors()
    finally:
        page.close()

    f = found["filter"]
    failed = []
    if not found["loaded"]:
        failed.append("the page did not finish loading")
    if found["errors"]:
        failed.append("errors: %s" % found["errors"])
    if not (f["every"] and f["shown"] == f["expected"] and f["none"] == 0 and f["restored"] == f["total"]):
        failed.append("the table did not filter: %s" % f)
    for clip in found["clips"]:
        if not (clip["playable"] and clip["loaded"]):
            failed.append("clip %s cannot be played" % clip["src"])
    found["passed"] = not failed
    found["failed"] = failed
    print(json.dumps(found))
    return 0 if not failed else 1


if __name__ == "__main__":
    sys.exit(main())
