# fprime-lite's framework configuration, in FPP.
#
# The aliases, enums and constants F´ v4's default configuration (config/FpConfig.fpp, the Linux
# platform types, config/ComCfg.fpp, config/DpCfg.fpp) defines and that fpp-to-dict needs when it
# builds a dictionary, with the values fprime-lite's framework uses (docs/fpp.md). Written for
# fprime-lite from the facts of F´'s configuration; not a copy of F´'s files.

# --- the platform (Linux): sizes and indices -------------------------------------------------
type PlatformSizeType = U64
type PlatformSignedSizeType = I64
type PlatformIndexType = I16
type PlatformAssertArgType = I32
type PlatformTaskPriorityType = U8
type PlatformTaskIdType = I32
type PlatformQueuePriorityType = U8

# --- sizes ------------------------------------------------------------------------------------
# The size of F´'s fixed-length strings (Fw::String), in bytes
constant FW_FIXED_LENGTH_STRING_SIZE = 256

# --- the framework's integer aliases ---------------------------------------------------------
type FwSizeType = PlatformSizeType
type FwSignedSizeType = PlatformSignedSizeType
type FwIndexType = PlatformIndexType
type FwAssertArgType = PlatformAssertArgType
type FwTaskPriorityType = PlatformTaskPriorityType
type FwQueuePriorityType = PlatformQueuePriorityType
type FwTaskIdType = PlatformTaskIdType

# Every id (opcode, event, channel, parameter) is a U32.
# `dictionary`: fprime-lite's dictionary lists these for the ground system whether or not a
# command, event, channel or parameter uses them (docs/fpp.md).
type FwIdType = U32
type FwChanIdType = FwIdType
type FwDpIdType = FwIdType
type FwDpPriorityType = U32
type FwEventIdType = FwIdType
type FwOpcodeType = FwIdType
type FwPrmIdType = FwIdType
type FwSizeStoreType = U16
type FwTimeContextStoreType = U8
type FwTlmPacketizeIdType = U16
type FwTraceIdType = U32
type FwEnumStoreType = I32
type FwTimeBaseStoreType = U16
type FwPacketDescriptorType = U16

# Time bases (fprime-lite flies TB_WORKSTATION_TIME on its simulated clock)
enum TimeBase : FwTimeBaseStoreType {
  TB_NONE = 0
  TB_PROC_TIME = 1
  TB_WORKSTATION_TIME = 2
  TB_DONT_CARE = 0xFFFF
} default TB_NONE

module ComCfg {

  # The spacecraft id of CCSDS frames
  constant SpacecraftId = 0x0044

  # The fixed size of a CCSDS TM frame, in bytes
  constant TmFrameFixedSize = 1024

  # The APID (packet type) of F´ packets
  enum Apid : FwPacketDescriptorType {
    FW_PACKET_COMMAND = 0x0000
    FW_PACKET_TELEM = 0x0001
    FW_PACKET_LOG = 0x0002
    FW_PACKET_FILE = 0x0003
    FW_PACKET_PACKETIZED_TLM = 0x0004
    FW_PACKET_DP = 0x0005
    FW_PACKET_IDLE = 0x0006
    FW_PACKET_HAND = 0x00FE
    FW_PACKET_UNKNOWN = 0x00FF
    SPP_IDLE_PACKET = 0x07FF
  } default FW_PACKET_UNKNOWN

}

module Fw {

  # The state of a data product (fprime-lite has no data products; fpp-to-dict asks for it)
  enum DpState : U8 {
    UNTRANSMITTED = 0
    PARTIAL = 1
    TRANSMITTED = 2
  } default UNTRANSMITTED

  module DpCfg {
    constant CONTAINER_USER_DATA_SIZE = 32
    enum ProcType : U8 {
      PROC_TYPE_NONE = 0x00
      PROC_TYPE_ZLIB_DEFLATE = 0x01
      PROC_TYPE_ONE = 0x02
      PROC_TYPE_TWO = 0x04
    }
  }

}
