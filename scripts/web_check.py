#!/usr/bin/env python3
"""Checks the visualiser's web page in headless Chromium (standard library
only: the DevTools protocol over a minimal WebSocket client).

    web_check.py URL LINK NAME [--shots DIR] [--speed-link LINK2]

URL is the served index.html, LINK a `tirecontact share` link (relative to
URL's folder) of a scene named NAME. Checks, failing with a message:

1. the page starts: its title ends in "— tirecontact", the canvas is drawn
   (a screenshot has many colours, not one), no console error or uncaught
   exception;
2. LINK opens its scene: the title becomes "NAME (from a link) — tirecontact";
3. Play (Space) advances the run's time (`data-time-s` on <body>).

With --hash-link LINK2 NAME2, LINK2's fragment set on the open page (a
link pasted into its address bar) must open NAME2's scene.

4. phones (390x844 and 360x740, touch emulated): the link opens there, the
   canvas has `touch-action: none`, and a synthetic swipe over it logs no
   console error (with `touch-action: auto` each swipe logged about 40
   "Unable to preventDefault inside passive event listener");
5. the link cut short is refused: the page opens without its scene
   ("(from a link)" not in the title), with no console error.

With --shots, screenshots at 1280x720, 412x915, 390x844 and 360x740 go
to DIR. With
--speed-link, the steps per second of that link's scene at the fastest
speed are measured and printed.
"""

import argparse
import base64
import json
import os
import random
import shutil
import socket
import struct
import subprocess
import sys
import tempfile
import time
import urllib.request
import zlib


class WebSocket:
    """A client WebSocket (RFC 6455) enough for the DevTools protocol."""

    def __init__(self, url):
        assert url.startswith("ws://")
        hostport, path = url[5:].split("/", 1)
        host, port = hostport.split(":")
        self.sock = socket.create_connection((host, int(port)), timeout=60)
        key = base64.b64encode(os.urandom(16)).decode()
        self.sock.sendall(
            (
                f"GET /{path} HTTP/1.1\r\nHost: {hostport}\r\nUpgrade: websocket\r\n"
                f"Connection: Upgrade\r\nSec-WebSocket-Key: {key}\r\n"
                "Sec-WebSocket-Version: 13\r\n\r\n"
            ).encode()
        )
        head = b""
        while b"\r\n\r\n" not in head:
            chunk = self.sock.recv(4096)
            if not chunk:
                raise RuntimeError("websocket handshake: connection closed")
            head += chunk
        head, self.buf = head.split(b"\r\n\r\n", 1)
        if b" 101 " not in head.split(b"\r\n")[0]:
            raise RuntimeError(f"websocket handshake refused: {head[:200]!r}")

    def send(self, text):
        data = text.encode()
        mask = os.urandom(4)
        n = len(data)
        if n < 126:
            header = struct.pack("!BB", 0x81, 0x80 | n)
        elif n < 65536:
            header = struct.pack("!BBH", 0x81, 0x80 | 126, n)
        else:
            header = struct.pack("!BBQ", 0x81, 0x80 | 127, n)
        masked = bytes(b ^ mask[i % 4] for i, b in enumerate(data))
        self.sock.sendall(header + mask + masked)

    def _read(self, n):
        while len(self.buf) < n:
            chunk = self.sock.recv(1 << 16)
            if not chunk:
                raise RuntimeError("websocket closed")
            self.buf += chunk
        out, self.buf = self.buf[:n], self.buf[n:]
        return out

    def recv(self):
        message = b""
        while True:
            b0, b1 = self._read(2)
            n = b1 & 0x7F
            if n == 126:
                (n,) = struct.unpack("!H", self._read(2))
            elif n == 127:
                (n,) = struct.unpack("!Q", self._read(8))
            payload = self._read(n)
            opcode = b0 & 0x0F
            if opcode == 0x8:
                raise RuntimeError("websocket closed by the browser")
            if opcode in (0x9, 0xA):
                continue
            message += payload
            if b0 & 0x80:
                return message.decode()


class Browser:
    """Headless Chromium driven through one page's DevTools session."""

    def __init__(self, chromium, width, height):
        self.profile = tempfile.mkdtemp(prefix="tc-web-check-")
        port = free_port()
        self.proc = subprocess.Popen(
            [
                chromium,
                "--headless",
                "--no-sandbox",
                "--enable-unsafe-swiftshader",
                "--use-angle=swiftshader",
                "--no-first-run",
                "--no-default-browser-check",
                "--disable-gpu-sandbox",
                "--disable-dev-shm-usage",
                f"--user-data-dir={self.profile}",
                f"--remote-debugging-port={port}",
                "--remote-allow-origins=*",
                f"--window-size={width},{height}",
                "about:blank",
            ],
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
        )
        deadline = time.time() + 60
        targets = None
        while time.time() < deadline:
            try:
                with urllib.request.urlopen(f"http://127.0.0.1:{port}/json", timeout=2) as r:
                    targets = [t for t in json.load(r) if t.get("type") == "page"]
                if targets:
                    break
            except OSError:
                pass
            time.sleep(0.2)
        if not targets:
            self.close()
            raise RuntimeError("chromium did not open its DevTools port")
        self.ws = WebSocket(targets[0]["webSocketDebuggerUrl"])
        self.next_id = 0
        self.errors = []
        self.call("Runtime.enable")
        self.call("Log.enable")
        self.call("Page.enable")
        self.resize(width, height)

    def close(self):
        try:
            self.proc.terminate()
            self.proc.wait(timeout=10)
        except Exception:
            self.proc.kill()
        shutil.rmtree(self.profile, ignore_errors=True)

    def _event(self, msg):
        method = msg.get("method")
        params = msg.get("params", {})
        if method == "Runtime.consoleAPICalled" and params.get("type") in ("error", "assert"):
            args = " ".join(str(a.get("value", a.get("description", ""))) for a in params["args"])
            self.errors.append(f"console.{params['type']}: {args}")
        elif method == "Runtime.exceptionThrown":
            d = params["exceptionDetails"]
            text = d.get("exception", {}).get("description") or d.get("text")
            self.errors.append(f"uncaught: {text}")
        elif method == "Log.entryAdded" and params["entry"].get("level") == "error":
            e = params["entry"]
            self.errors.append(f"log ({e.get('source')}): {e.get('text')} {e.get('url', '')}")

    def call(self, method, **params):
        self.next_id += 1
        me = self.next_id
        self.ws.send(json.dumps({"id": me, "method": method, "params": params}))
        while True:
            msg = json.loads(self.ws.recv())
            if msg.get("id") == me:
                if "error" in msg:
                    raise RuntimeError(f"{method}: {msg['error']}")
                return msg.get("result", {})
            self._event(msg)

    def pump(self, seconds):
        """Lets the page run for `seconds`, reading its events."""
        end = time.time() + seconds
        while time.time() < end:
            self.evaluate("1")
            time.sleep(0.05)

    def resize(self, width, height, mobile=False):
        self.call(
            "Emulation.setDeviceMetricsOverride",
            width=width,
            height=height,
            deviceScaleFactor=1,
            mobile=mobile,
        )
        if mobile:
            self.call("Emulation.setTouchEmulationEnabled", enabled=True, maxTouchPoints=5)

    def swipe(self, x, y0, y1, steps=12):
        """A one-finger vertical swipe from (x, y0) to (x, y1)."""
        self.call("Input.dispatchTouchEvent", type="touchStart", touchPoints=[{"x": x, "y": y0}])
        for k in range(1, steps + 1):
            y = y0 + (y1 - y0) * k / steps
            self.call("Input.dispatchTouchEvent", type="touchMove", touchPoints=[{"x": x, "y": y}])
            time.sleep(0.02)
        self.call("Input.dispatchTouchEvent", type="touchEnd", touchPoints=[])

    def evaluate(self, expr):
        r = self.call("Runtime.evaluate", expression=expr, returnByValue=True)
        return r.get("result", {}).get("value")

    def navigate(self, url):
        self.call("Page.navigate", url=url)

    def wait_for(self, what, predicate, timeout):
        end = time.time() + timeout
        value = None
        while time.time() < end:
            value = predicate()
            if value:
                return value
            self.pump(0.2)
        raise AssertionError(f"timed out after {timeout} s waiting for {what} (last: {value!r})")

    def title(self):
        return self.evaluate("document.title") or ""

    def time_s(self):
        v = self.evaluate("document.body && document.body.dataset.timeS")
        return float(v) if v else None

    def steps(self):
        v = self.evaluate("document.body && document.body.dataset.steps")
        return int(v) if v else None

    def screenshot(self):
        data = self.call("Page.captureScreenshot", format="png")["data"]
        return base64.b64decode(data)

    def key(self, key, code, vk):
        for kind in ("keyDown", "keyUp"):
            self.call(
                "Input.dispatchKeyEvent",
                type=kind,
                key=key,
                code=code,
                windowsVirtualKeyCode=vk,
                nativeVirtualKeyCode=vk,
                text=key if kind == "keyDown" and len(key) == 1 else "",
            )

    def click(self, x, y):
        for kind in ("mouseMoved", "mousePressed", "mouseReleased"):
            self.call(
                "Input.dispatchMouseEvent",
                type=kind,
                x=x,
                y=y,
                button="left" if kind != "mouseMoved" else "none",
                clickCount=1,
            )


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def png_colours(png):
    """The number of distinct RGB colours of an 8-bit RGB(A) PNG."""
    assert png[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
    pos, idat, width, height, ctype = 8, b"", 0, 0, 0
    while pos < len(png):
        (n,) = struct.unpack("!I", png[pos : pos + 4])
        kind = png[pos + 4 : pos + 8]
        body = png[pos + 8 : pos + 8 + n]
        if kind == b"IHDR":
            width, height, depth, ctype = struct.unpack("!IIBB", body[:10])
            assert depth == 8 and ctype in (2, 6), f"PNG depth {depth} colour type {ctype}"
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    bpp = 3 if ctype == 2 else 4
    raw = zlib.decompress(idat)
    stride = width * bpp
    prev = bytearray(stride)
    colours = set()
    for y in range(height):
        f = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1 : (y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b = prev[i]
            c = prev[i - bpp] if i >= bpp else 0
            if f == 1:
                line[i] = (line[i] + a) & 0xFF
            elif f == 2:
                line[i] = (line[i] + b) & 0xFF
            elif f == 3:
                line[i] = (line[i] + (a + b) // 2) & 0xFF
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                pr = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
                line[i] = (line[i] + pr) & 0xFF
        if y % 4 == 0:
            for x in range(0, stride, bpp * 4):
                colours.add(bytes(line[x : x + 3]))
        prev = line
    return len(colours)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("url")
    ap.add_argument("link")
    ap.add_argument("name")
    ap.add_argument("--shots")
    ap.add_argument("--speed-link")
    ap.add_argument("--realtime-link")
    ap.add_argument("--dt", type=float, default=1e-5)
    ap.add_argument("--hash-link", nargs=2, metavar=("LINK", "NAME"))
    ap.add_argument("--chromium", default=shutil.which("chromium") or "chromium")
    args = ap.parse_args()
    folder = args.url.rsplit("/", 1)[0]
    b = Browser(args.chromium, 1280, 720)
    try:
        # 1. the page starts and draws
        b.navigate(args.url)
        b.wait_for("the app's title", lambda: b.title().endswith("— tirecontact"), 120)
        b.wait_for("the run's time on <body>", lambda: b.time_s() is not None, 30)
        b.pump(2)
        shot = b.screenshot()
        colours = png_colours(shot)
        assert colours >= 20, f"the page looks blank: {colours} colours in its screenshot"
        print(f"web-check: page started, title {b.title()!r}, {colours} colours drawn")
        if args.shots:
            os.makedirs(args.shots, exist_ok=True)
            with open(os.path.join(args.shots, "web_1280x720.png"), "wb") as f:
                f.write(shot)

        # 2. a share link opens its scene (a new query, so the page loads again)
        b.navigate(f"{folder}/{args.link.replace('index.html', 'index.html?' + str(random.random()), 1)}")
        want = f"{args.name} (from a link) — tirecontact"
        b.wait_for(f"title {want!r}", lambda: b.title() == want, 120)
        print(f"web-check: the link opened {want!r}")
        if args.hash_link:
            # another link pasted into the open page's address bar
            fragment = args.hash_link[0].split("#", 1)[1]
            b.evaluate(f"location.hash = {json.dumps(fragment)}")
            other = f"{args.hash_link[1]} (from a link) — tirecontact"
            b.wait_for(f"title {other!r}", lambda: b.title() == other, 120)
            print(f"web-check: a link pasted into the open page opened {other!r}")
            b.navigate(f"{folder}/{args.link.replace('index.html', 'index.html?' + str(random.random()), 1)}")
            b.wait_for(f"title {want!r}", lambda: b.title() == want, 120)

        # 3. Play (Space, the canvas focused) advances the time
        b.wait_for("the run's time", lambda: b.time_s() is not None, 30)
        t0 = b.time_s()
        b.click(1270, 715)
        b.key(" ", "Space", 32)
        b.wait_for("the time to advance after Play", lambda: (b.time_s() or 0) > t0, 30)
        print(f"web-check: Play advanced the time from {t0} s to {b.time_s()} s")
        if args.shots:
            b.pump(2)
            with open(os.path.join(args.shots, "web_1280x720_playing.png"), "wb") as f:
                f.write(b.screenshot())
            # a phone opens the page at its size, with nothing kept from before
            phone = Browser(args.chromium, 412, 915)
            try:
                phone.navigate(f"{folder}/{args.link}&view=2")
                phone.wait_for(f"title {want!r}", lambda: phone.title() == want, 120)
                phone.pump(1)
                phone.click(400, 905)
                phone.key(" ", "Space", 32)
                phone.pump(3)
                with open(os.path.join(args.shots, "web_412x915.png"), "wb") as f:
                    f.write(phone.screenshot())
                b.errors += phone.errors
            finally:
                phone.close()

        # 4. phones: a touch screen, a swipe over the canvas
        for (w, h) in ((390, 844), (360, 740)):
            phone = Browser(args.chromium, w, h)
            try:
                phone.resize(w, h, mobile=True)
                phone.navigate(f"{folder}/{args.link.replace('index.html', 'index.html?' + str(random.random()), 1)}")
                phone.wait_for(f"title {want!r} at {w}x{h}", lambda: phone.title() == want, 120)
                phone.pump(1)
                touch = phone.evaluate("getComputedStyle(document.getElementById('tirecontact')).touchAction")
                assert touch == "none", f"the canvas has touch-action {touch!r} at {w}x{h}"
                before = len(phone.errors)
                for _ in range(3):
                    phone.swipe(w // 2, int(0.7 * h), int(0.3 * h))
                    phone.pump(0.3)
                logged = phone.errors[before:]
                assert not logged, f"a swipe at {w}x{h} logged {len(logged)} errors: {logged[:3]}"
                print(f"web-check: {w}x{h}: touch-action none, three swipes logged no error")
                if args.shots:
                    with open(os.path.join(args.shots, f"web_{w}x{h}.png"), "wb") as f:
                        f.write(phone.screenshot())
                b.errors += phone.errors
            finally:
                phone.close()

        # 5. the link cut short, in a browser with no session kept: refused,
        # the page opens on its default scene
        fresh = Browser(args.chromium, 1280, 720)
        try:
            cut = args.link[: len(args.link) - 40]
            fresh.navigate(f"{folder}/{cut}")
            fresh.wait_for("the page after a cut link", lambda: fresh.title().endswith("— tirecontact"), 120)
            fresh.pump(1)
            title = fresh.title()
            assert "(from a link)" not in title and args.name not in title, f"a cut link opened {title!r}"
            print(f"web-check: the link cut short was refused (title {title!r})")
            if args.shots:
                with open(os.path.join(args.shots, "web_cut_link.png"), "wb") as f:
                    f.write(fresh.screenshot())
            b.errors += fresh.errors
        finally:
            fresh.close()

        if args.speed_link:
            b.navigate(f"{folder}/{args.speed_link.replace('index.html', 'index.html?' + str(random.random()), 1)}")
            b.wait_for("the speed scene", lambda: b.steps() == 0 and b.title() != want, 120)
            b.pump(1)
            b.click(1270, 715)
            b.key(" ", "Space", 32)
            b.wait_for("the run to start", lambda: (b.steps() or 0) > 0, 30)
            # the browser's frames, counted by requestAnimationFrame
            b.evaluate(
                "window.__frames = 0; (function f() { window.__frames++; requestAnimationFrame(f); })()"
            )
            s0, f0, w0 = b.steps(), b.evaluate("window.__frames"), time.time()
            b.pump(10)
            s1, f1, w1 = b.steps(), b.evaluate("window.__frames"), time.time()
            rate = (s1 - s0) / (w1 - w0)
            fps = (f1 - f0) / (w1 - w0)
            # at the fastest speed the solver takes its whole budget each
            # frame (12 ms, or half the interval between slower frames)
            print(
                f"web-check: speed {rate:.0f} steps/s in the page ({s1 - s0} steps in {w1 - w0:.1f} s, "
                f"{fps:.1f} frames/s, {rate / max(fps, 1e-9):.0f} steps a frame)"
            )

        if args.realtime_link:
            # the same scene at the speed it opens at (1x for a run of 4 s or more)
            b.navigate(f"{folder}/{args.realtime_link.replace('index.html', 'index.html?' + str(random.random()), 1)}")
            b.wait_for("the real-time scene", lambda: b.steps() == 0, 120)
            b.pump(1)
            b.click(1270, 715)
            b.key(" ", "Space", 32)
            b.wait_for("the run to start", lambda: (b.steps() or 0) > 0, 30)
            s0, w0 = b.steps(), time.time()
            b.pump(10)
            s1, w1 = b.steps(), time.time()
            print(
                f"web-check: at the speed it opens at, the page plays {(s1 - s0) * args.dt / (w1 - w0):.2f}x "
                f"real time ({s1 - s0} steps of {args.dt:g} s in {w1 - w0:.1f} s)"
            )

        b.pump(0.5)
        if b.errors:
            raise AssertionError("console errors:\n  " + "\n  ".join(b.errors))
        print("web-check: no console errors")
    finally:
        b.close()


if __name__ == "__main__":
    try:
        main()
    except AssertionError as e:
        print(f"web-check: FAILED: {e}", file=sys.stderr)
        sys.exit(1)
