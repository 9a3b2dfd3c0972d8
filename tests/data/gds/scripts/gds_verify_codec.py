# Reference only: run with the fprime-gds 4.4.1 venv python; NOT collected by the project test-suite.
import struct
import zlib
from fprime_gds.common.models.dictionaries import Dictionaries
from fprime_gds.common.data_types.cmd_data import CmdData
from fprime_gds.common.encoders.cmd_encoder import CmdEncoder
from fprime_gds.common.decoders.event_decoder import EventDecoder
from fprime_gds.common.decoders.ch_decoder import ChDecoder
from fprime_gds.common.communication.framing import FpFramerDeframer
from fprime_gds.common.communication.ccsds.chain import SpacePacketSpaceDataLinkFramerDeframer
from fprime_gds.common.communication.ccsds.space_data_link import SpaceDataLinkFramerDeframer

d = Dictionaries.load_dictionaries_into_config(str(__import__("pathlib").Path(__file__).resolve().parent.parent / "minimal_dictionary.json"))
# ---- command encode
cmd = CmdData(["7", "2.5", "hello", "NOMINAL"], d.command_name["MiniDep.demo.CONFIGURE"])
ground = CmdEncoder().encode_api(cmd)
print("CmdEncoder output:", ground.hex(" "))
packet = ground[8:]        # strip 'ZZZZ'(0x5A5A5A5A) + U32 length -> what FSW receives inside a frame
print("FSW packet       :", packet.hex(" "))
fp = FpFramerDeframer("crc32").frame(packet)
print("fprime frame     :", fp.hex(" "))
assert fp[:4] == b"\xde\xad\xbe\xef" and struct.unpack(">I", fp[4:8])[0] == len(packet)
assert struct.unpack(">I", fp[-4:])[0] == zlib.crc32(fp[:-4])
# deframe with garbage and keep-alive in front
pk, rest, disc = FpFramerDeframer().deframe(b"sitting well" + fp + b"xx")
assert pk == packet and rest == b"xx" and disc == b"sitting well"
# ---- event packet by hand: U16 desc(2) | U32 id | time(U16 base,U8 ctx,U32 s,U32 us) | args
def t(base=2, ctx=0, s=100, us=250000): return struct.pack(">HBII", base, ctx, s, us)
ev_args = struct.pack(">If", 7, 2.5) + struct.pack(">H", 5) + b"hello" + struct.pack(">i", 1)
ev_pkt = struct.pack(">H", 2) + struct.pack(">I", 0x1000) + t() + ev_args   # ONE event per packet (see notes)
two = ev_pkt + struct.pack(">I", 0x101) + t(s=101) + struct.pack(">I", 0x1000)
try:
    EventDecoder(d.event_id).decode_api(two[2:]); print("two events in one packet: decoded")
except Exception as exc:
    print("two events in one packet: FAILS ->", type(exc).__name__)
for e in EventDecoder(d.event_id).decode_api(ev_pkt[2:]):   # decoders get payload after the descriptor
    print("event:", e.get_template().get_full_name(), e.get_time().seconds, e.get_time().useconds, [a.val for a in e.get_args()], "|", e.get_str())
# ---- channel packet by hand: U16 desc(1) | U32 id | time | value   (repeated)
ch_pkt = struct.pack(">H", 1) + struct.pack(">I", 0x1000) + t() + struct.pack(">f", 3.3) \
       + struct.pack(">I", 0x1001) + t() + struct.pack(">fff", 1, 2, 3) \
       + struct.pack(">I", 0x1002) + t() + struct.pack(">i", 2)
for c in ChDecoder(d.channel_id).decode_api(ch_pkt[2:]):
    print("channel:", c.get_template().get_full_name(), c.get_val_obj().val, c.get_str())
# ---- CCSDS uplink (TC frame around a Space Packet)
ccsds = SpacePacketSpaceDataLinkFramerDeframer(scid=None, vcid=1, frame_size=None)
tc = ccsds.frame(packet)
print("TC frame         :", tc.hex(" "))
# ---- CCSDS downlink: build one 1024-byte TM frame by hand: event Space Packet + idle packet filling the rest
FRAME = 1024
def space_packet(apid, payload, seq=0, tm=True):
    w1 = (0 << 13) | ((0 if tm else 1) << 12) | (0 << 11) | apid
    w2 = (0b11 << 14) | seq
    return struct.pack(">HHH", w1, w2, len(payload) - 1) + payload
sp = space_packet(2, ev_pkt)          # APID = packet descriptor (FW_PACKET_LOG=2); payload starts with the U16 descriptor
field_len = FRAME - 6 - 2
idle_len = field_len - len(sp)
idle = space_packet(0x7FF, b"\x00" * (idle_len - 6))
scid, vcid = 0x44, 1
hdr = struct.pack(">HBBH", (0 << 14) | (scid << 4) | (vcid << 1) | 0, 0, 0, 0x0000 | 0)  # MC count 0, VC count 0, FHP 0
body = hdr + sp + idle
tm = body + struct.pack(">H", SpaceDataLinkFramerDeframer.CCITT_CRC_FUNCTION(body))
assert len(tm) == FRAME
pkts, rest, disc = ccsds.deframe_all(b"sitting well" + tm, no_copy=False)
print("TM deframed packets:", [p.hex()[:24] + "..." for p in pkts], "rest", len(rest), "discarded", disc)
assert pkts == [ev_pkt]
