"""Fake flight software speaking fprime framing to a running fprime-gds (TCP client)."""
import socket
import struct
import time
import zlib
import sys
import threading
def frame(pkt):
    h = struct.pack(">II", 0xDEADBEEF, len(pkt)) + pkt
    return h + struct.pack(">I", zlib.crc32(h))
def t():
    now = time.time(); return struct.pack(">HBII", 2, 0, int(now), int((now % 1) * 1e6))
def event(eid, args): return struct.pack(">HI", 2, eid) + t() + args
def chan(cid, val): return struct.pack(">HI", 1, cid) + t() + val
log = open("fake_fsw_fprime.log", "w")
s = socket.create_connection(("127.0.0.1", int(sys.argv[1]) if len(sys.argv) > 1 else 50000))
buf = b""; dispatched = 0; keepalive = 0
def tlm():
    while True:
        # one telemetry packet holding two channel records
        s.sendall(frame(chan(0x1000, struct.pack(">f", 3.3)) + struct.pack(">I", 0x100) + t() + struct.pack(">I", dispatched)))
        time.sleep(0.5)
threading.Thread(target=tlm, daemon=True).start()
end = time.time() + float(sys.argv[2] if len(sys.argv) > 2 else 60)
s.settimeout(0.5)
while time.time() < end:
    try: data = s.recv(4096)
    except socket.timeout: continue
    if not data: break
    buf += data
    while True:
        i = buf.find(b"\xde\xad\xbe\xef")
        if i < 0:
            keepalive += buf.count(b"sitting well"); buf = buf[-3:]; break
        keepalive += buf[:i].count(b"sitting well")
        buf = buf[i:]
        if len(buf) < 8: break
        n = struct.unpack(">I", buf[4:8])[0]
        if len(buf) < 12 + n: break
        f, buf = buf[:12 + n], buf[12 + n:]
        assert struct.unpack(">I", f[-4:])[0] == zlib.crc32(f[:-4])
        pkt = f[8:-4]
        desc, opcode = struct.unpack(">HI", pkt[:6])
        log.write(f"RX frame {f.hex(' ')} desc={desc} opcode={opcode:#x} args={pkt[6:].hex()}\n"); log.flush()
        dispatched += 1
        s.sendall(frame(event(0x100, struct.pack(">Ii", opcode, 0))))
        s.sendall(frame(event(0x101, struct.pack(">I", opcode))))
        if opcode == 0x1000:
            s.sendall(frame(event(0x1000, pkt[6:])))
log.write(f"keepalives seen: {keepalive}\n"); log.close()
