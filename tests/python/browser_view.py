#!/usr/bin/env python3
"""Checks a `touchdown view` page in headless Chromium, with the standard library only.

usage: python3 browser_view.py CHROMIUM HTML_FILE OUT_DIR

Starts Chromium, drives the page over the Chrome DevTools Protocol (a WebSocket client
written here on `socket`), and checks: no console errors; the 3D canvas is drawn; moving the
time slider with the mouse changes the picture and the charts' cursor; dragging on the
canvas orbits and the wheel zooms; on a page with rocks or regolith, that the pointer over
the view names a rock (its radius) or a sunk footpad (its sinkage). Saves
OUT_DIR/view-before.png and view-after.png. Prints one line per check; exits 0 when all
pass, 1 when one fails, 3 when Chromium cannot start. Every wait is bounded; Chromium is always killed and its profile removed.
"""
import base64, hashlib, http.client, json, os, queue, re, shutil, signal, socket, struct
import subprocess, sys, tempfile, threading, time, urllib.parse

TOTAL_S = 55  # the whole script, hard limit
WS_GUID = b"258EAFA5-E914-47DA-95CA-C5AB0DC85B11"


class Timeout(Exception):
    """A bounded wait ran out."""


class StartError(Exception):
    """Chromium did not start (or did not say where its DevTools endpoint is)."""


class WebSocket:
    """A minimal RFC 6455 client: text frames out (masked), whole messages in."""

    def __init__(self, url, timeout=10.0):
        u = urllib.parse.urlparse(url)
        self.sock = socket.create_connection((u.hostname, u.port or 80), timeout=timeout)
        key = base64.b64encode(os.urandom(16)).decode()
        self.sock.sendall((f"GET {u.path or '/'} HTTP/1.1\r\nHost: {u.hostname}:{u.port}\r\n"
                           "Upgrade: websocket\r\nConnection: Upgrade\r\n"
                           f"Sec-WebSocket-Key: {key}\r\nSec-WebSocket-Version: 13\r\n\r\n").encode())
        self.buf = b""
        while b"\r\n\r\n" not in self.buf:
            chunk = self.sock.recv(4096)
            if not chunk:
                raise ConnectionError("WebSocket handshake: connection closed")
            self.buf += chunk
        head, self.buf = self.buf.split(b"\r\n\r\n", 1)
        accept = base64.b64encode(hashlib.sha1(key.encode() + WS_GUID).digest())
        if not head.startswith(b"HTTP/1.1 101") or accept not in head:
            raise ConnectionError(f"WebSocket handshake refused: {head[:200]!r}")

    def _exact(self, n, deadline):
        while len(self.buf) < n:
            try:
                self.sock.settimeout(max(1e-3, deadline - time.monotonic()))
                chunk = self.sock.recv(max(65536, n - len(self.buf)))
            except socket.timeout:
                raise Timeout("no message from Chromium in time") from None
            if not chunk:
                raise ConnectionError("WebSocket closed by Chromium")
            self.buf += chunk
        out, self.buf = self.buf[:n], self.buf[n:]
        return out

    def _frame(self, opcode, payload):
        """One final frame, masked (a client must mask), with a 7-, 16- or 64-bit length."""
        n = len(payload)
        head = struct.pack(">BB", 0x80 | opcode, 0x80 | n) if n < 126 else \
            struct.pack(">BBH", 0x80 | opcode, 0x80 | 126, n) if n < 1 << 16 else \
            struct.pack(">BBQ", 0x80 | opcode, 0x80 | 127, n)
        mask = os.urandom(4)
        self.sock.sendall(head + mask + self._mask(payload, mask))

    @staticmethod
    def _mask(payload, mask):
        """XOR with the repeated 4-byte key, as one big integer (fast for large frames)."""
        n = len(payload)
        if n == 0:
            return b""
        key = int.from_bytes((mask * (n // 4 + 1))[:n], "big")
        return (int.from_bytes(payload, "big") ^ key).to_bytes(n, "big")

    def send(self, text):
        self._frame(0x1, text.encode())

    def recv(self, deadline):
        """The next whole text message (fragments joined; pings answered)."""
        parts = []
        while True:
            b0, b1 = self._exact(2, deadline)
            opcode, n = b0 & 0x0F, b1 & 0x7F
            if n == 126:
                n = struct.unpack(">H", self._exact(2, deadline))[0]
            elif n == 127:
                n = struct.unpack(">Q", self._exact(8, deadline))[0]
            mask = self._exact(4, deadline) if b1 & 0x80 else None
            data = self._exact(n, deadline)
            if mask:
                data = self._mask(data, mask)
            if opcode == 0x8:
                raise ConnectionError("WebSocket closed by Chromium")
            if opcode == 0x9:  # ping: answer; pong: ignore
                self._frame(0xA, data)
            if opcode in (0x9, 0xA):
                continue
            parts.append(data)
            if b0 & 0x80:
                return b"".join(parts).decode("utf-8", "replace")

    def close(self):
        self.sock.close()


class CDP:
    """Commands and events over one DevTools WebSocket."""

    def __init__(self, ws):
        self.ws, self.next_id, self.events, self.errors = ws, 0, [], []

    def _event(self, msg):
        self.events.append(msg)
        m, p = msg.get("method"), msg.get("params", {})
        if m == "Runtime.exceptionThrown":
            d = p.get("exceptionDetails", {})
            self.errors.append("exception: " + (d.get("exception", {}).get("description") or d.get("text", "?")))
        elif m == "Runtime.consoleAPICalled" and p.get("type") in ("error", "assert"):
            args = " ".join(str(a.get("value", a.get("description", ""))) for a in p.get("args", []))
            self.errors.append(f"console.{p.get('type')}: {args}")
        elif m == "Log.entryAdded" and p.get("entry", {}).get("level") == "error":
            e = p["entry"]
            self.errors.append(f"log: {e.get('text')} {e.get('url', '')}".strip())

    def call(self, method, params=None, timeout=10.0):
        self.next_id += 1
        me = self.next_id
        self.ws.send(json.dumps({"id": me, "method": method, "params": params or {}}))
        deadline = time.monotonic() + timeout
        while True:
            msg = json.loads(self.ws.recv(deadline))
            if "method" in msg:
                self._event(msg)
            elif msg.get("id") == me:
                if "error" in msg:
                    raise RuntimeError(f"{method}: {msg['error'].get('message')}")
                return msg.get("result", {})

    def wait_event(self, name, since, timeout):
        deadline = time.monotonic() + timeout
        while True:
            if any(e.get("method") == name for e in self.events[since:]):
                return
            self._event(json.loads(self.ws.recv(deadline)))

    def evaluate(self, expr, awaited=False, timeout=10.0):
        r = self.call("Runtime.evaluate", {"expression": expr, "returnByValue": True,
                                           "awaitPromise": awaited}, timeout)
        if "exceptionDetails" in r:
            raise RuntimeError(f"evaluate failed: {r['exceptionDetails'].get('text')} in {expr[:60]}")
        return r.get("result", {}).get("value")


def start_chromium(chromium, profile):
    args = [chromium, "--headless", "--no-sandbox", "--disable-gpu", "--remote-debugging-port=0",
            f"--user-data-dir={profile}", "--window-size=1280,900", "--no-first-run",
            "--no-default-browser-check", "--hide-scrollbars", "about:blank"]
    try:
        proc = subprocess.Popen(args, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                                stderr=subprocess.PIPE, start_new_session=True)
    except OSError as e:
        raise StartError(f"cannot run {chromium}: {e}") from None
    lines = queue.Queue()

    def drain():  # keep reading stderr so that Chromium never blocks on it
        for raw in proc.stderr:
            lines.put(raw.decode("utf-8", "replace").rstrip())
        lines.put(None)
    threading.Thread(target=drain, daemon=True).start()
    seen, deadline = [], time.monotonic() + 20
    while time.monotonic() < deadline:
        try:
            line = lines.get(timeout=max(0.01, deadline - time.monotonic()))
        except queue.Empty:
            line = None
        if line is None:
            break
        seen.append(line)
        m = re.search(r"DevTools listening on (ws://\S+)", line)
        if m:
            return proc, m.group(1)
    stop_chromium(proc)
    why = "exited" if proc.poll() is not None else "no 'DevTools listening' line in 20 s"
    raise StartError(f"{why}; stderr: " + " | ".join(seen[-6:]))


def stop_chromium(proc):
    if proc is None:
        return
    for sig, wait in ((signal.SIGTERM, 3), (signal.SIGKILL, 3)):
        try:
            os.killpg(proc.pid, sig)  # its own session: the browser and its helpers
        except (ProcessLookupError, PermissionError):
            pass
        try:
            proc.wait(timeout=wait)
        except subprocess.TimeoutExpired:
            continue


def open_page(browser_url):
    """A page target's WebSocket URL: /json/new (PUT, then GET), else Target.createTarget."""
    u = urllib.parse.urlparse(browser_url)
    for verb in ("PUT", "GET"):
        try:
            c = http.client.HTTPConnection(u.hostname, u.port, timeout=5)
            c.request(verb, "/json/new?about:blank")
            r = c.getresponse()
            if r.status == 200:
                return json.loads(r.read())["webSocketDebuggerUrl"]
        except (OSError, ValueError, KeyError, http.client.HTTPException):
            pass
    ws = WebSocket(browser_url)
    try:
        tid = CDP(ws).call("Target.createTarget", {"url": "about:blank"})["targetId"]
    finally:
        ws.close()
    return f"ws://{u.hostname}:{u.port}/devtools/page/{tid}"


CANVAS_STATS = """(() => {
  const c = document.getElementById('view3d');
  const px = new Uint32Array(c.getContext('2d').getImageData(0, 0, c.width, c.height).data.buffer);
  const counts = new Map(); let h = 2166136261;
  for (let i = 0; i < px.length; i++) {
    const v = px[i]; counts.set(v, (counts.get(v) || 0) + 1); h = Math.imul(h ^ v, 16777619) >>> 0;
  }
  let bg = 0, most = -1;
  for (const [v, n] of counts) if (n > most) { bg = v; most = n; }
  return {w: c.width, h: c.height, nonbg: px.length - most, distinct: counts.size, hash: h,
          bg: [bg & 255, (bg >> 8) & 255, (bg >> 16) & 255]};  // RGBA bytes, little-endian
})()"""
# The same of a WebGL canvas (drawn with preserveDrawingBuffer): copied into a 2D canvas.
_PIXELS_2D = "const px = new Uint32Array(c.getContext('2d').getImageData(0, 0, c.width, c.height).data.buffer);"
assert _PIXELS_2D in CANVAS_STATS
WEBGL_CANVAS_STATS = CANVAS_STATS.replace(_PIXELS_2D, (
    "const t = document.createElement('canvas'); t.width = c.width; t.height = c.height;\n"
    "  const g = t.getContext('2d'); g.drawImage(c, 0, 0);\n"
    "  const px = new Uint32Array(g.getImageData(0, 0, t.width, t.height).data.buffer);"))
REPAINT = "new Promise(r => requestAnimationFrame(() => requestAnimationFrame(() => r(true))))"
CURSOR = """(() => { const s = document.getElementById('time');
  return [s.value, window.touchdownCursorTime, s.max]; })()"""
BOX = """(() => { const r = document.getElementById('%s').getBoundingClientRect();
  return {x: r.x, y: r.y, w: r.width, h: r.height}; })()"""


def run_checks(page, html, out_dir):
    fails = []

    def check(good, text):
        print(("ok: " if good else "FAIL: ") + text, flush=True)
        if not good:
            fails.append(text)
        return good

    for domain in ("Runtime", "Log", "Page"):
        page.call(f"{domain}.enable")
    since = len(page.events)
    nav = page.call("Page.navigate", {"url": "file://" + os.path.abspath(html)})
    if nav.get("errorText"):
        check(False, f"navigate to {html}: {nav['errorText']}")
        return 1
    page.wait_event("Page.loadEventFired", since, 15)
    deadline = time.monotonic() + 15
    while page.evaluate("window.touchdownViewReady === true") is not True:
        if time.monotonic() > deadline:
            check(False, "window.touchdownViewReady not true within 15 s")
            return 1
        time.sleep(0.1)
    check(True, "page loaded and ready")

    def repaint():
        page.evaluate(REPAINT, awaited=True)

    def settled():
        """The canvas's stats once two looks 0.2 s apart agree (the camera eases; at most 4 s)."""
        last, deadline = None, time.monotonic() + 4
        while True:
            repaint()
            now = page.evaluate(CANVAS_STATS)
            if (last and now["hash"] == last["hash"]) or time.monotonic() > deadline:
                return now
            last = now
            time.sleep(0.2)

    def mouse(kind, x, y, **extra):
        page.call("Input.dispatchMouseEvent", dict(type=kind, x=x, y=y, **extra))

    def shot(name):
        data = base64.b64decode(page.call("Page.captureScreenshot", {"format": "png"}, 15)["data"])
        with open(os.path.join(out_dir, name), "wb") as f:
            f.write(data)
        return data

    st = settled()
    share = st["nonbg"] / max(1, st["w"] * st["h"])
    check(share > 0.02 and st["distinct"] > 8,
          f"3D canvas drawn: {st['w']}x{st['h']} px, {100 * share:.1f} % differ from the background "
          f"(the commonest colour, rgb{tuple(st['bg'])}), {st['distinct']} distinct colours")

    # Move the time slider as a user would: press, drag a little, release at ~80 % of its track.
    before_png, before = shot("view-before.png"), st
    value0, cursor0, _ = page.evaluate(CURSOR)
    box = page.evaluate(BOX % "time")
    x, y = box["x"] + 0.8 * box["w"], box["y"] + box["h"] / 2
    mouse("mouseMoved", x - 3, y)
    mouse("mousePressed", x - 3, y, button="left", buttons=1, clickCount=1)
    mouse("mouseMoved", x, y, button="left", buttons=1)
    mouse("mouseReleased", x, y, button="left", buttons=0, clickCount=1)
    after = settled()
    value1, cursor1, top = page.evaluate(CURSOR)
    check(value1 != value0, f"slider moved by the mouse: value {value0} -> {value1} (max {top})")
    check(cursor1 != cursor0, f"chart cursor time {cursor0} -> {cursor1}")
    after_png = shot("view-after.png")
    check(after_png != before_png, f"screenshots differ ({len(before_png)} vs {len(after_png)} bytes)")
    check(after["hash"] != before["hash"], f"3D canvas changed with the slider "
          f"(hash {before['hash']:08x} -> {after['hash']:08x})")

    # Orbit: drag across the (now still) canvas.
    box = page.evaluate(BOX % "view3d")
    cx, cy = box["x"] + box["w"] / 2, box["y"] + box["h"] / 2
    mouse("mouseMoved", cx, cy)
    mouse("mousePressed", cx, cy, button="left", buttons=1, clickCount=1)
    for k in range(1, 7):
        mouse("mouseMoved", cx + 25 * k, cy + 6 * k, button="left", buttons=1)
    mouse("mouseReleased", cx + 150, cy + 36, button="left", buttons=0, clickCount=1)
    orbit = settled()
    check(orbit["hash"] != after["hash"], f"orbit drag changed the 3D view (hash {orbit['hash']:08x})")

    # Zoom: one wheel notch in.
    mouse("mouseWheel", cx, cy, deltaX=0, deltaY=-240)
    zoom = settled()
    check(zoom["hash"] != orbit["hash"], f"wheel zoom changed the 3D view (hash {zoom['hash']:08x})")

    # Hover, on a page with rocks or regolith: sweep the pointer over the view (no button)
    # and collect what the page names under it.
    kinds = page.evaluate("(function () { const d = JSON.parse(document.getElementById("
                          "'trace-data').textContent); return [Array.isArray(d.rocks), "
                          "d.regolith === true]; })()")
    if any(kinds):
        box = page.evaluate(BOX % "view3d")
        seen = set()

        def found():
            """What the checks below look for is named (the sweep stops there)."""
            rock = any(t.startswith("rock: radius") for t in seen)
            sunk = any(" sunk " in t for t in seen)
            return (rock or not kinds[0]) and (sunk or not kinds[1])
        for j in range(1, 24):
            for i in range(1, 32):
                mouse("mouseMoved", box["x"] + box["w"] * i / 32, box["y"] + box["h"] * j / 24)
                text = page.evaluate("window.touchdownHover || ''")
                if text:
                    seen.add(text)
            if found():
                break
        named = sorted(seen)
        if kinds[0]:
            check(any(t.startswith("rock: radius") for t in named),
                  f"hover names rocks ({len(named)} texts, e.g. {named[:3]})")
        if kinds[1]:
            check(any(" sunk " in t for t in named),
                  f"hover names a sunk footpad ({[t for t in named if 'footpad' in t][:4]})")

    repaint()
    check(not page.errors, "no console errors" if not page.errors else
          f"{len(page.errors)} console error(s): " + " || ".join(page.errors[:10]))
    return 1 if fails else 0


def main():
    if len(sys.argv) != 4:
        print(__doc__.strip().splitlines()[2], file=sys.stderr)
        return 2
    chromium, html, out_dir = sys.argv[1:]
    os.makedirs(out_dir, exist_ok=True)

    def expired(*_):
        raise Timeout(f"the check took over {TOTAL_S} s")
    signal.signal(signal.SIGALRM, expired)
    signal.alarm(TOTAL_S)
    profile, proc, ws = tempfile.mkdtemp(prefix="touchdown-view-"), None, None
    try:
        try:
            proc, browser_url = start_chromium(chromium, profile)
        except StartError as e:
            print(f"FAIL: Chromium cannot start: {e}", flush=True)
            return 3
        ws = WebSocket(open_page(browser_url))
        return run_checks(CDP(ws), html, out_dir)
    except (Timeout, ConnectionError, OSError, RuntimeError, ValueError, KeyError) as e:
        print(f"FAIL: {type(e).__name__}: {e}", flush=True)
        return 1
    finally:
        signal.alarm(0)
        if ws:
            ws.sock.close()
        stop_chromium(proc)
        shutil.rmtree(profile, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
