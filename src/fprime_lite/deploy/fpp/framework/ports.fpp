# fprime-lite's framework ports and the types they carry, in FPP.
#
# The port types of F´'s Fw and Svc modules that fprime-lite implements (src/fprime_lite/model/
# fw_ports.py and the services of src/fprime_lite/svc/), with F´'s names and arguments, so that a
# component or topology written against F´'s framework analyses here. Written for fprime-lite from
# the facts of F´ v4's port signatures; not a copy of F´'s files. The named types these ports and
# the services use (Fw.CmdResponse, Svc.VersionStatus ...) are in svc.fpp, which fprime-lite
# writes from its own implementation (`python -m fprime_lite.deploy.fpp.export --framework`).

module Fw {

  @ Serialized buffers and strings the framework passes by reference
  type CmdArgBuffer
  type LogBuffer
  type TlmBuffer
  type ParamBuffer
  type ComBuffer
  type Buffer
  type TextLogString
  type String

  @ A time stamp (the abstract type the time ports pass)
  type Time

  # A time stamp's value, as the dictionary describes a time argument
  struct TimeValue {
    timeBase: TimeBase
    timeContext: FwTimeContextStoreType
    seconds: U32
    useconds: U32
  }

  @ The severity of an event
  enum LogSeverity : U32 {
    FATAL = 1
    WARNING_HI = 2
    WARNING_LO = 3
    COMMAND = 4
    ACTIVITY_HI = 5
    ACTIVITY_LO = 6
    DIAGNOSTIC = 7
  } default FATAL

  @ Whether a telemetry value read back is valid
  enum TlmValid { VALID = 0, INVALID = 1 }

  @ Whether a parameter value read back is valid
  enum ParamValid { UNINIT = 0, VALID = 1, INVALID = 2, DEFAULT = 3 }

  port Cmd(opCode: FwOpcodeType, cmdSeq: U32, ref args: CmdArgBuffer)
  port CmdReg(opCode: FwOpcodeType)
  port CmdResponse(opCode: FwOpcodeType, cmdSeq: U32, response: CmdResponse)
  port Log($id: FwEventIdType, ref timeTag: Time, $severity: LogSeverity, ref args: LogBuffer)
  port LogText($id: FwEventIdType, ref timeTag: Time, $severity: LogSeverity, ref $text: TextLogString)
  port Tlm($id: FwChanIdType, ref timeTag: Time, ref val: TlmBuffer)
  port TlmGet($id: FwChanIdType, ref timeTag: Time, ref val: TlmBuffer) -> TlmValid
  port PrmGet($id: FwPrmIdType, ref val: ParamBuffer) -> ParamValid
  port PrmSet($id: FwPrmIdType, ref val: ParamBuffer)
  port Time(ref $time: Fw.Time)
  port Com(ref data: ComBuffer, context: U32)
  port BufferSend(ref fwBuffer: Fw.Buffer)
  port Signal()

  # The level of a digital line
  enum Logic { HIGH = 0, LOW = 1 }

}

module Drv {

  # F´'s GPIO driver ports (a PROVES load switch drives one); fprime-lite's simulated drivers do
  # not implement them
  enum GpioStatus { OP_OK = 0, NOT_OPENED = 1, INVALID_MODE = 2, UNKNOWN_ERROR = 3 }
  port GpioWrite($state: Fw.Logic) -> GpioStatus
  port GpioRead(ref $state: Fw.Logic) -> GpioStatus

}

module Svc {

  port Sched(context: U32)
  port Cycle(ref cycleStart: Fw.Time)
  port Ping(key: U32)
  port FatalEvent(Id: FwEventIdType)
  port CmdSeqIn(ref filename: Fw.String)
  port CmdSeqCancel()
  port WatchDog(code: U32)
  port FileAnnounce(ref file_name: Fw.String)
  # The time interface a time source implements (F´ v4: `import Svc.Time`)
  interface Time {
    sync input port timeGetPort: Fw.Time
  }

  port Version(ref version_id: VersionCfg.VersionEnum, ref version_string: Fw.String, ref status: VersionStatus)

}
