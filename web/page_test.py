#!/usr/bin/env python3
"""The sandbox page in a real browser: serves the built page on 127.0.0.1, opens it in
headless Chromium through chromedriver (WebDriver), waits for the app's first frames, clicks
the terrain and checks from screenshots that a crater appeared where it clicked, then drops
a level file (levels/caverns.ron) onto the page and checks that the terrain changed to it.
First it opens the page in a Chromium without WebGPU, which must get the page's message
instead.

    web/page_test.py PAGE_DIR ARTIFACT_DIR

The screenshots before and after the click are kept in ARTIFACT_DIR. Exits non-zero, with
what it saw, when the page does not start (no WebGPU: the page says so), draws no frames,
the click leaves the ground as it was, or the dropped level does not replace the terrain.
Standard library only.
"""

import base64
import functools
import http.server
import json
import os
import socket
import struct
import subprocess
import sys
import threading
import time
import urllib.error
import urllib.request
import zlib

CHROMEDRIVER = os.environ.get("CHROMEDRIVER", "/usr/bin/chromedriver")
CHROMIUM = os.environ.get("CHROMIUM", "/usr/bin/chromium")
WINDOW = (1280, 800)
# The sandbox's side panel is 340 points wide on the right; the terrain view is the rest.
PANEL = 340
START_TIMEOUT_S = 180
FRAMES_BEFORE_CLICK = 10


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def serve(directory):
    """Serves `directory` on a free loopback port from a thread; returns the base URL."""
    handler = functools.partial(QuietHandler, directory=directory)
    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
    threading.Thread(target=server.serve_forever, daemon=True).start()
    return f"http://127.0.0.1:{server.server_address[1]}/"


class QuietHandler(http.server.SimpleHTTPRequestHandler):
    def log_message(self, *args):
        pass


class WebDriver:
    """The few WebDriver commands the test needs, over chromedriver's HTTP API."""

    def __init__(self, webgpu=True):
        self.port = free_port()
        self.proc = subprocess.Popen(
            [CHROMEDRIVER, f"--port={self.port}"],
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
        )
        self.base = f"http://127.0.0.1:{self.port}"
        deadline = time.time() + 30
        while True:
            try:
                if self.call("GET", "/status")["ready"]:
                    break
            except OSError:
                pass
            if time.time() > deadline:
                raise RuntimeError("chromedriver did not start within 30 s")
            time.sleep(0.2)
        args = [
            "--headless=new",
            "--no-sandbox",
            "--disable-dev-shm-usage",
            f"--window-size={WINDOW[0]},{WINDOW[1]}",
        ]
        if webgpu:
            args += [
                "--enable-unsafe-webgpu",
                # Headless Chromium composites a WebGPU canvas into screenshots only with
                # SwiftShader's Vulkan (without these the screenshot is blank white).
                "--enable-features=Vulkan",
                "--use-vulkan=swiftshader",
                "--use-angle=swiftshader",
                "--enable-unsafe-swiftshader",
            ]
        args += os.environ.get("CHROMIUM_ARGS", "").split()
        caps = {"capabilities": {"alwaysMatch": {
            "browserName": "chrome",
            "goog:chromeOptions": {"binary": CHROMIUM, "args": args},
            "goog:loggingPrefs": {"browser": "ALL"},
        }}}
        self.session = self.call("POST", "/session", caps)["sessionId"]

    def call(self, method, path, body=None):
        data = None if body is None else json.dumps(body).encode()
        req = urllib.request.Request(self.base + path, data=data, method=method,
                                     headers={"Content-Type": "application/json"})
        try:
            with urllib.request.urlopen(req, timeout=120) as r:
                return json.load(r)["value"]
        except urllib.error.HTTPError as e:
            raise RuntimeError(f"WebDriver {method} {path}: {e.read().decode()[:500]}")

    def cmd(self, method, path, body=None):
        return self.call(method, f"/session/{self.session}{path}", body)

    def script(self, js):
        return self.cmd("POST", "/execute/sync", {"script": js, "args": []})

    def screenshot(self):
        return base64.b64decode(self.cmd("GET", "/screenshot"))

    def click(self, x, y):
        pointer = {"type": "pointer", "id": "mouse", "parameters": {"pointerType": "mouse"},
                   "actions": [
                       {"type": "pointerMove", "duration": 0, "x": x, "y": y, "origin": "viewport"},
                       {"type": "pointerDown", "button": 0},
                       {"type": "pause", "duration": 60},
                       {"type": "pointerUp", "button": 0},
                   ]}
        self.cmd("POST", "/actions", {"actions": [pointer]})

    def console(self):
        """The page's console messages since the last call."""
        try:
            entries = self.cmd("POST", "/se/log", {"type": "browser"})
        except RuntimeError:
            return []
        return [f"{e.get('level')}: {e.get('message')}" for e in entries]

    def close(self):
        try:
            self.cmd("DELETE", "")
        finally:
            self.proc.terminate()


def decode_png(data):
    """(width, height, rows of (r, g, b) tuples) of an 8-bit RGB or RGBA PNG."""
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
    pos, idat = 8, b""
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        chunk = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            width, height, depth, color, _, _, interlace = struct.unpack(">IIBBBBB", chunk)
            assert depth == 8 and color in (2, 6) and interlace == 0, "unsupported PNG"
        elif kind == b"IDAT":
            idat += chunk
        pos += 12 + length
    bpp = 3 if color == 2 else 4
    raw, stride = zlib.decompress(idat), width * bpp
    rows, prev = [], bytearray(stride)
    for y in range(height):
        f, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b, c = prev[i], prev[i - bpp] if i >= bpp else 0
            if f == 1:
                line[i] = (line[i] + a) & 255
            elif f == 2:
                line[i] = (line[i] + b) & 255
            elif f == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append([tuple(line[x * bpp:x * bpp + 3]) for x in range(width)])
        prev = line
    return width, height, rows


def wait_for(what, check, timeout):
    deadline = time.time() + timeout
    while time.time() < deadline:
        value = check()
        if value:
            return value
        time.sleep(0.5)
    raise RuntimeError(f"timed out after {timeout} s waiting for {what}")


def ground_point(rows, width, height):
    """A point of the terrain view deep in the ground: the pixel whose 9x9 neighbourhood
    has one colour and differs most from the top row's sky, searched in the view's middle."""
    view_right = width - PANEL
    sky = rows[5][view_right // 2]
    best = None
    for y in range(height // 3, height - 20, 8):
        for x in range(view_right // 5, view_right * 4 // 5, 8):
            c = rows[y][x]
            if any(rows[y + dy][x + dx] != c for dy in (-4, 0, 4) for dx in (-4, 0, 4)):
                continue
            score = sum(abs(c[k] - sky[k]) for k in range(3))
            if best is None or score > best[0]:
                best = (score, x, y)
    if best is None or best[0] < 60:
        raise RuntimeError("found no ground in the terrain view (is the level drawn?)")
    return best[1], best[2]


def changed_near(before, after, x, y, radius):
    """Fraction of pixels within `radius` of (x, y) whose colour changed visibly."""
    total = changed = 0
    for yy in range(y - radius, y + radius + 1):
        for xx in range(x - radius, x + radius + 1):
            if (xx - x) ** 2 + (yy - y) ** 2 > radius ** 2:
                continue
            total += 1
            a, b = before[yy][xx], after[yy][xx]
            changed += sum(abs(a[k] - b[k]) for k in range(3)) > 30
    return changed / total


def drop_file(driver, name, text):
    """Drops a file named `name` holding `text` onto the sandbox's canvas, as a user dragging
    it from the desktop would (a drag-enter, a drag-over and a drop carrying the file)."""
    driver.script(
        "const dt = new DataTransfer();"
        f"dt.items.add(new File([{json.dumps(text)}], {json.dumps(name)}));"
        "const canvas = document.getElementById('sandbox');"
        "for (const type of ['dragenter', 'dragover', 'drop']) {"
        "  canvas.dispatchEvent(new DragEvent(type,"
        "    {bubbles: true, cancelable: true, dataTransfer: dt}));"
        "}")


def changed_in_view(before, after, width):
    """The share of the terrain view's pixels (left of the panel) that changed."""
    view = max(1, width - PANEL)
    changed = total = 0
    for row_a, row_b in zip(before, after):
        for x in range(0, view, 2):
            total += 1
            changed += row_a[x] != row_b[x]
    return changed / max(total, 1)


def without_webgpu(url):
    """Chromium on Linux offers WebGPU only behind a flag: without it the page must say
    that the browser has no WebGPU, and start nothing."""
    driver = WebDriver(webgpu=False)
    try:
        driver.cmd("POST", "/url", {"url": url})
        state = wait_for("the page to give up", lambda: driver.script(
            "return document.body.dataset.state === 'loading' ? null : document.body.dataset.state"),
            START_TIMEOUT_S)
        text = driver.script("return document.getElementById('message').textContent")
        if state != "error" or "WebGPU" not in text:
            raise RuntimeError(f"without WebGPU the page is {state!r} and says {text!r}")
        print(f"page test: without WebGPU the page says: {text}", flush=True)
    finally:
        driver.close()


def main(page_dir, artifacts):
    os.makedirs(artifacts, exist_ok=True)
    url = serve(page_dir)
    without_webgpu(url)
    driver = WebDriver()
    try:
        driver.cmd("POST", "/url", {"url": url})
        state = wait_for("the page to start", lambda: driver.script(
            "return document.body.dataset.state === 'loading' ? null : document.body.dataset.state"),
            START_TIMEOUT_S)
        if state != "running":
            text = driver.script("return document.getElementById('message').textContent")
            raise RuntimeError(f"the page did not start: {text}")
        started = time.time()
        wait_for(f"{FRAMES_BEFORE_CLICK} frames", lambda: driver.script(
            f"return window.craterfieldFrames() >= {FRAMES_BEFORE_CLICK}"), START_TIMEOUT_S)
        frames = driver.script("return window.craterfieldFrames()")
        fps = frames / max(time.time() - started, 1e-3)
        print(f"page test: running; {frames} frames drawn, about {fps:.1f} frames/s", flush=True)
        before_png = driver.screenshot()
        with open(os.path.join(artifacts, "sandbox-before.png"), "wb") as f:
            f.write(before_png)
        width, height, before = decode_png(before_png)
        x, y = ground_point(before, width, height)
        driver.click(x, y)
        mark = driver.script("return window.craterfieldFrames()")
        wait_for("frames after the click", lambda: driver.script(
            f"return window.craterfieldFrames() >= {mark + 6}"), START_TIMEOUT_S)
        after_png = driver.screenshot()
        _, _, after = decode_png(after_png)
        with open(os.path.join(artifacts, "sandbox.png"), "wb") as f:
            f.write(after_png)
        inner = changed_near(before, after, x, y, 4)
        far = changed_near(before, after, x, y, 60) if min(x, y) > 60 else 0.0
        print(f"page test: clicked the ground at ({x}, {y}); {100 * inner:.0f}% of the pixels "
              f"within 4 px changed, {100 * far:.0f}% within 60 px; screenshots in {artifacts}")
        if inner < 0.8:
            raise RuntimeError("no crater appeared where the page was clicked")
        level = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "levels",
                             "caverns.ron")
        with open(level, encoding="utf-8") as f:
            drop_file(driver, "caverns.ron", f.read())
        mark = driver.script("return window.craterfieldFrames()")
        wait_for("frames after the drop", lambda: driver.script(
            f"return window.craterfieldFrames() >= {mark + 6}"), START_TIMEOUT_S)
        dropped_png = driver.screenshot()
        with open(os.path.join(artifacts, "sandbox-dropped-level.png"), "wb") as f:
            f.write(dropped_png)
        _, _, dropped = decode_png(dropped_png)
        share = changed_in_view(after, dropped, width)
        print(f"page test: dropped levels/caverns.ron on the page; {100 * share:.0f}% of the "
              f"terrain view changed")
        if share < 0.2:
            raise RuntimeError("the dropped level did not replace the terrain")
        times = sorted(driver.script("return Array.from(window.craterfieldFrameTimes())"))
        at = lambda p: times[max(0, min(len(times), -(-len(times) * p // 100)) - 1)]
        print(f"page test: {len(times)} frame intervals at {width}x{height} (SwiftShader, on "
              f"the CPU): median {at(50):.1f} ms, p95 {at(95):.1f}, p99 {at(99):.1f}, "
              f"max {times[-1]:.1f}")
    except RuntimeError:
        for line in driver.console()[-40:]:
            print("page console:", line[:400], file=sys.stderr)
        raise
    finally:
        driver.close()


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    try:
        main(sys.argv[1], sys.argv[2])
    except RuntimeError as e:
        sys.exit(f"page test failed: {e}")
    print("page test: passed")
