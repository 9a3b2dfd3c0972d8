"""Screenshot the fprime-gds web UI held open in headless Chromium, through the DevTools protocol.

The web UI lists only the events that arrive after the page opened, so a one-shot
``chromium --screenshot`` shows an empty table: the page must stay open while the deployment
flies. Start Chromium (as root) with its DevTools endpoint on loopback, send some commands, then:

    chromium --headless --no-sandbox --disable-gpu --disable-background-networking \
      --disable-component-update --disable-sync --no-first-run --user-data-dir="$(mktemp -d)" \
      --remote-debugging-address=127.0.0.1 --remote-debugging-port=9333 --window-size=1400,900 \
      'http://127.0.0.1:5000/#Events' &
    python docs/img/gds_screenshot.py 9333 docs/img/gds_ui.png 3     # port, output, seconds to wait

Standard library only (a minimal RFC 6455 client); loopback addresses only. Not used by the tests.
"""
import base64, json, os, socket, struct, sys, time, urllib.request

def ws_connect(url):
    assert url.startswith("ws://127.0.0.1:")
    hostport, path = url[5:].split("/", 1)
    host, port = hostport.split(":")
    s = socket.create_connection((host, int(port)), timeout=30)
    key = base64.b64encode(os.urandom(16)).decode()
    s.sendall((f"GET /{path} HTTP/1.1\r\nHost: {hostport}\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n"
               f"Sec-WebSocket-Key: {key}\r\nSec-WebSocket-Version: 13\r\n\r\n").encode())
    resp = b""
    while b"\r\n\r\n" not in resp:
        resp += s.recv(1)
    assert b" 101 " in resp.split(b"\r\n")[0], resp
    return s

def ws_send(s, text):
    data = text.encode(); mask = os.urandom(4)
    n = len(data)
    head = bytes([0x81]) + (bytes([0x80 | n]) if n < 126 else bytes([0x80 | 126]) + struct.pack(">H", n) if n < 65536
                            else bytes([0x80 | 127]) + struct.pack(">Q", n))
    s.sendall(head + mask + bytes(b ^ mask[i % 4] for i, b in enumerate(data)))

def recv_exact(s, n):
    buf = b""
    while len(buf) < n:
        chunk = s.recv(n - len(buf)); assert chunk; buf += chunk
    return buf

def ws_recv(s):
    b0, b1 = recv_exact(s, 2)
    n = b1 & 0x7F
    if n == 126: n = struct.unpack(">H", recv_exact(s, 2))[0]
    elif n == 127: n = struct.unpack(">Q", recv_exact(s, 8))[0]
    return recv_exact(s, n).decode()

port, out, wait_s = int(sys.argv[1]), sys.argv[2], float(sys.argv[3])
pages = json.load(urllib.request.urlopen(f"http://127.0.0.1:{port}/json"))
page = [p for p in pages if p["type"] == "page"][0]
s = ws_connect(page["webSocketDebuggerUrl"])
time.sleep(wait_s)
ws_send(s, json.dumps({"id": 1, "method": "Page.captureScreenshot", "params": {"format": "png"}}))
while True:
    msg = json.loads(ws_recv(s))
    if msg.get("id") == 1:
        open(out, "wb").write(base64.b64decode(msg["result"]["data"])); break
print("saved", out)
