"""Fake FSW speaking the default CCSDS framing (space-packet-space-data-link) to fprime-gds."""
import socket
import struct
import time
import sys
import crcmod
crc16 = crcmod.mkCrcFun(0x11021, initCrc=0xFFFF, xorOut=0, rev=False)
SCID, VCID, FRAME = 0x44, 1, 1024
seq = {}; vc = [0]
def t(): now = time.time(); return struct.pack(">HBII", 2, 0, int(now), int((now % 1) * 1e6))
def sp(apid, payload):
    c = seq.get(apid, 0); seq[apid] = (c + 1) % 16384
    return struct.pack(">HHH", apid & 0x7FF, (0b11 << 14) | c, len(payload) - 1) + payload
def tm(packets):
    field = b"".join(packets); room = FRAME - 8 - len(field)
    assert room >= 7 or room == 0
    if room: field += struct.pack(">HHH", 0x7FF, 0xC000, room - 7) + b"\x00" * (room - 6)
    hdr = struct.pack(">HBBH", (SCID << 4) | (VCID << 1), vc[0], vc[0], 0)   # FHP 0: packet starts at field[0]
    vc[0] = (vc[0] + 1) % 256
    body = hdr + field
    return body + struct.pack(">H", crc16(body))
log = open("fake_fsw_ccsds.log", "w")
s = socket.create_connection(("127.0.0.1", int(sys.argv[1]))); s.settimeout(0.5)
buf = b""; end = time.time() + float(sys.argv[2]); last = 0
while time.time() < end:
    if time.time() - last > 0.5:
        last = time.time()
        s.sendall(tm([sp(1, struct.pack(">HI", 1, 0x1000) + t() + struct.pack(">f", 3.3))]))
    try: data = s.recv(4096)
    except socket.timeout: continue
    if not data: break
    buf += data
    while True:
        i = buf.find(b"\x20\x44")            # TC header word 1: bypass + SCID 0x44
        if i < 0: buf = buf[-1:]; break
        buf = buf[i:]
        if len(buf) < 5: break
        n = (struct.unpack(">H", buf[2:4])[0] & 0x3FF) + 1
        if len(buf) < n: break
        f, buf = buf[:n], buf[n:]
        if crc16(f[:-2]) != struct.unpack(">H", f[-2:])[0]: log.write("bad crc\n"); continue
        pkt = f[5 + 6:-2]
        desc, opcode = struct.unpack(">HI", pkt[:6])
        log.write(f"RX TC {f.hex(' ')}\n   desc={desc} opcode={opcode:#x}\n"); log.flush()
        s.sendall(tm([sp(2, struct.pack(">HI", 2, 0x100) + t() + struct.pack(">Ii", opcode, 0)),
                      sp(2, struct.pack(">HI", 2, 0x101) + t() + struct.pack(">I", opcode))]))
