# Written by fprime-lite (python -m fprime_lite.deploy.fpp.export --framework) from the services in src/fprime_lite/svc/ and the Fw types of src/fprime_lite/model/fw_types.py.
# Regenerate it rather than edit it; tests/fprime_lite/deploy/test_fpp.py checks it is current.

module Fw {
  enum CmdResponse : U8 {
    OK = 0
    INVALID_OPCODE = 1
    VALIDATION_ERROR = 2
    FORMAT_ERROR = 3
    EXECUTION_ERROR = 4
    BUSY = 5
    CLEARED = 6
  } default OK

  enum DeserialStatus : I32 {
    OK = 0
    BUFFER_EMPTY = 3
    FORMAT_ERROR = 4
    SIZE_MISMATCH = 5
    TYPE_MISMATCH = 6
  } default OK

  enum FwEnabled : I32 {
    DISABLED = 0
    ENABLED = 1
  } default DISABLED

  enum On : I32 {
    OFF = 0
    ON = 1
  } default OFF

  enum StringFormatStatus : U8 {
    SUCCESS = 0
    OVERFLOWED = 1
    INVALID_FORMAT_STRING = 2
    SIZE_OVERFLOW = 3
    OTHER_ERROR = 4
  } default SUCCESS

  enum Success : U8 {
    SUCCESS = 0
    FAILURE = 1
  } default SUCCESS

  struct TimeIntervalValue {
    seconds: U32
    useconds: U32
  } default { seconds = 0, useconds = 0 }
}

module Svc {
  struct CustomVersionDb {
    version_enum: Svc.VersionCfg.VersionEnum
    version_value: string size 80
    version_status: Svc.VersionStatus
  } default { version_enum = Svc.VersionCfg.VersionEnum.PROJECT_VERSION_00, version_value = "", version_status = Svc.VersionStatus.OK }

  struct SendFileResponse {
    status: Svc.SendFileStatus
    context: U32
  } default { status = Svc.SendFileStatus.STATUS_OK, context = 0 }

  enum SendFileStatus : I32 {
    STATUS_OK = 0
    STATUS_ERROR = 1
    STATUS_INVALID = 2
    STATUS_BUSY = 3
  } default STATUS_OK

  enum VersionEnabled : I32 {
    DISABLED = 0
    ENABLED = 1
  } default DISABLED

  enum VersionStatus : I32 {
    OK = 0
    FAILURE = 1
  } default OK

  enum VersionType : I32 {
    PROJECT = 0
    FRAMEWORK = 1
    LIBRARY = 2
    CUSTOM = 3
    ALL = 4
  } default PROJECT

  port SendFileComplete($resp: Svc.SendFileResponse)

  port SendFileRequest(sourceFileName: string size 100, destFileName: string size 100, offset: U32, length: U32) -> Svc.SendFileResponse

  active component CommandDispatcher {
    time get port timeCaller
    command recv port cmdIn
    command reg port cmdRegOut
    command resp port cmdResponseOut
    event port logOut
    text event port logTextOut
    telemetry port tlmOut
    guarded input port compCmdReg: [64] Fw.CmdReg
    async input port seqCmdBuff: [8] Fw.Com priority 0 hook
    async input port compCmdStat: Fw.CmdResponse priority 0 assert
    async input port run: Svc.Sched priority 0 assert
    async input port pingIn: Svc.Ping priority 0 assert
    output port compCmdSend: [64] Fw.Cmd
    output port seqCmdStatus: [8] Fw.CmdResponse
    output port pingOut: Svc.Ping
    async command CMD_NO_OP opcode 0x0 priority 0 assert
    async command CMD_NO_OP_STRING(arg1: string size 40) opcode 0x1 priority 0 assert
    async command CMD_TEST_CMD_1(arg1: I32, arg2: F32, arg3: U8) opcode 0x2 priority 0 assert
    async command CMD_CLEAR_TRACKING opcode 0x3 priority 0 assert
    event OpCodeRegistered(Opcode: U32, $port: I32, slot: I32) severity diagnostic id 0x0 format "Opcode 0x{x} registered to port {} slot {}"
    event OpCodeDispatched(Opcode: U32, $port: I32) severity command id 0x1 format "Opcode 0x{x} dispatched to port {}"
    event OpCodeCompleted(Opcode: U32) severity command id 0x2 format "Opcode 0x{x} completed"
    event OpCodeError(Opcode: U32, error: Fw.CmdResponse) severity command id 0x3 format "Opcode 0x{x} completed with error {}"
    event MalformedCommand(Status: Fw.DeserialStatus) severity warning high id 0x4 format "Received malformed command packet. Status: {}"
    event InvalidCommand(Opcode: U32) severity warning high id 0x5 format "Invalid opcode 0x{x} received"
    event TooManyCommands(Opcode: U32) severity warning high id 0x6 format "Too many outstanding commands. opcode=0x{x}"
    event NoOpReceived severity activity high id 0x7 format "Received a NO-OP command"
    event NoOpStringReceived(message: string size 40) severity activity high id 0x8 format "Received a NO-OP string={}"
    event TestCmd1Args(arg1: I32, arg2: F32, arg3: U8) severity activity high id 0x9 format "TEST_CMD_1 args: I32: {}, F32: {f}, U8: {}"
    event OpCodeReregistered(Opcode: U32, $port: I32) severity diagnostic id 0xA format "Opcode 0x{x} is already registered to port {}"
    event CommandDroppedQueueOverflow(OpCode: U32, Context: U32) severity warning high id 0xB format "Opcode 0x{x} was dropped due to buffer overflow and not processed. Context {}" throttle 5
    event HandlerFault($port: string size 40, exception: string size 120) severity warning high id 0xC format "Handler {} raised {}" throttle 10
    telemetry CommandsDispatched: U32 id 0x0 update on change
    telemetry CommandErrors: U32 id 0x1 update on change
    telemetry CommandsDropped: U32 id 0x2 update on change
    telemetry HandlerFaults: U32 id 0x3 update on change
    match compCmdSend with compCmdReg
  }

  active component CmdSequencer {
    enum BlockState : I32 {
      BLOCK = 0
      NO_BLOCK = 1
    } default BLOCK
    enum FileReadStage : I32 {
      READ_HEADER = 0
      READ_HEADER_SIZE = 1
      DESER_SIZE = 2
      DESER_NUM_RECORDS = 3
      DESER_TIME_BASE = 4
      DESER_TIME_CONTEXT = 5
      READ_SEQ_CRC = 6
      READ_SEQ_DATA = 7
      READ_SEQ_DATA_SIZE = 8
    } default READ_HEADER
    enum SeqMode : I32 {
      STEP = 0
      AUTO = 1
    } default STEP
    time get port timeCaller
    command recv port cmdIn
    command reg port cmdRegOut
    command resp port cmdResponseOut
    event port logOut
    text event port logTextOut
    telemetry port tlmOut
    async input port cmdResponseIn: Fw.CmdResponse priority 0 assert
    async input port schedIn: Svc.Sched priority 0 assert
    async input port seqRunIn: Svc.CmdSeqIn priority 0 assert
    async input port seqCancelIn: Svc.CmdSeqCancel priority 0 assert
    async input port pingIn: Svc.Ping priority 0 assert
    output port pingOut: Svc.Ping
    output port seqDone: Fw.CmdResponse
    output port comCmdOut: Fw.Com
    output port seqStartOut: Svc.CmdSeqIn
    async command CS_RUN(fileName: string size 200, $block: Svc.CmdSequencer.BlockState) opcode 0x0 priority 0 assert
    async command CS_VALIDATE(fileName: string size 200) opcode 0x1 priority 0 assert
    async command CS_CANCEL opcode 0x2 priority 0 assert
    async command CS_START opcode 0x3 priority 0 assert
    async command CS_STEP opcode 0x4 priority 0 assert
    async command CS_AUTO opcode 0x5 priority 0 assert
    async command CS_MANUAL opcode 0x6 priority 0 assert
    async command CS_JOIN_WAIT opcode 0x7 priority 0 assert
    event CS_SequenceLoaded(fileName: string size 60) severity activity low id 0x0 format "Loaded sequence {}"
    event CS_SequenceCanceled(fileName: string size 60) severity activity high id 0x1 format "Sequence file {} canceled"
    event CS_FileReadError(fileName: string size 60) severity warning high id 0x2 format "Error reading sequence file {}"
    event CS_FileInvalid(fileName: string size 60, stage: Svc.CmdSequencer.FileReadStage, error: I32) severity warning high id 0x3 format "Sequence file {} invalid. Stage: {} Error: {}"
    event CS_RecordInvalid(fileName: string size 60, recordNumber: U32, error: I32) severity warning high id 0x4 format "Sequence file {}: Record {} invalid. Err: {}"
    event CS_FileSizeError(fileName: string size 60, $size: U32) severity warning high id 0x5 format "Sequence file {} too large. Size: {}"
    event CS_FileNotFound(fileName: string size 60) severity warning high id 0x6 format "Sequence file {} not found."
    event CS_FileCrcFailure(fileName: string size 60, storedCRC: U32, computedCRC: U32) severity warning high id 0x7 format "Sequence file {} had invalid CRC. Stored 0x{x}, Computed 0x{x}."
    event CS_CommandComplete(fileName: string size 60, recordNumber: U32, opCode: U32) severity activity low id 0x8 format "Sequence file {}: Command {} (opcode {}) complete"
    event CS_SequenceComplete(fileName: string size 60) severity activity high id 0x9 format "Sequence file {} complete"
    event CS_CommandError(fileName: string size 60, recordNumber: U32, opCode: U32, errorStatus: U32) severity warning high id 0xA format "Sequence file {}: Command {} (opcode {}) completed with error {}"
    event CS_InvalidMode severity warning high id 0xB format "Invalid mode"
    event CS_RecordMismatch(fileName: string size 60, header_records: U32, extra_bytes: U32) severity warning high id 0xC format "Sequence file {} header records mismatch: {} in header, found {} extra bytes."
    event CS_TimeBaseMismatch(fileName: string size 60, time_base: U16, seq_time_base: U16) severity warning high id 0xD format "Sequence file {}: Current time base doesn't match sequence time: base: {} seq: {}"
    event CS_TimeContextMismatch(fileName: string size 60, currTimeBase: U8, seqTimeBase: U8) severity warning high id 0xE format "Sequence file {}: Current time context doesn't match sequence context: base: {} seq: {}"
    event CS_PortSequenceStarted(filename: string size 60) severity activity high id 0xF format "Local request for sequence {} started."
    event CS_UnexpectedCompletion($opcode: U32) severity warning high id 0x10 format "Command complete status received while no sequences active. Opcode: {}"
    event CS_ModeSwitched(mode: Svc.CmdSequencer.SeqMode) severity activity high id 0x11 format "Sequencer switched to {} step mode"
    event CS_NoSequenceActive severity warning low id 0x12 format "No sequence active."
    event CS_SequenceValid(filename: string size 60) severity activity high id 0x13 format "Sequence {} is valid."
    event CS_SequenceTimeout(filename: string size 60, $command: U32) severity warning high id 0x14 format "Sequence {} timed out on command {}"
    event CS_CmdStepped(filename: string size 60, $command: U32) severity activity high id 0x15 format "Sequence {} command {} stepped"
    event CS_CmdStarted(filename: string size 60) severity activity high id 0x16 format "Sequence {} started"
    event CS_JoinWaiting(filename: string size 60, recordNumber: U32, opCode: U32) severity activity high id 0x17 format "Start waiting for sequence file {}: Command {} (opcode {}) to complete"
    event CS_JoinWaitingNotComplete severity warning high id 0x18 format "Still waiting for sequence file to complete"
    event CS_NoRecords(fileName: string size 60) severity warning low id 0x19 format "Sequence file {} has no records. Ignoring."
    event CS_TextFileInvalid(fileName: string size 60, lineNumber: U32, reason: string size 120) severity warning high id 0x40 format "Sequence file {} line {}: {}"
    event HandlerFault($port: string size 40, exception: string size 120) severity warning high id 0x41 format "Handler {} raised {}" throttle 10
    telemetry CS_LoadCommands: U32 id 0x0 update always
    telemetry CS_CancelCommands: U32 id 0x1 update always
    telemetry CS_Errors: U32 id 0x2 update always
    telemetry CS_CommandsExecuted: U32 id 0x3 update always
    telemetry CS_SequencesCompleted: U32 id 0x4 update always
    telemetry HandlerFaults: U32 id 0x5 update on change
  }

  active component EventManager {
    enum Enabled : U8 {
      ENABLED = 0
      DISABLED = 1
    } default ENABLED
    enum FilterSeverity : U8 {
      WARNING_HI = 0
      WARNING_LO = 1
      COMMAND = 2
      ACTIVITY_HI = 3
      ACTIVITY_LO = 4
      DIAGNOSTIC = 5
    } default WARNING_HI
    time get port timeCaller
    command recv port cmdIn
    command reg port cmdRegOut
    command resp port cmdResponseOut
    event port logOut
    text event port logTextOut
    telemetry port tlmOut
    sync input port LogRecv: Fw.Log
    async input port run: Svc.Sched priority 0 drop
    async input port pingIn: Svc.Ping priority 0 assert
    output port PktSend: Fw.Com
    output port FatalAnnounce: Svc.FatalEvent
    output port pingOut: Svc.Ping
    sync command SET_EVENT_FILTER(filterLevel: Svc.EventManager.FilterSeverity, filterEnabled: Svc.EventManager.Enabled) opcode 0x0
    async command SET_ID_FILTER(ID: U32, idFilterEnabled: Svc.EventManager.Enabled) opcode 0x2 priority 0 assert
    async command DUMP_FILTER_STATE opcode 0x3 priority 0 assert
    event SEVERITY_FILTER_STATE($severity: Svc.EventManager.FilterSeverity, enabled: bool) severity activity low id 0x0 format "{} filter state. {}"
    event ID_FILTER_ENABLED(ID: U32) severity activity high id 0x1 format "ID {} is filtered."
    event ID_FILTER_LIST_FULL(ID: U32) severity warning low id 0x2 format "ID filter list is full. Cannot filter {} ."
    event ID_FILTER_REMOVED(ID: U32) severity activity high id 0x3 format "ID filter ID {} removed."
    event ID_FILTER_NOT_FOUND(ID: U32) severity warning low id 0x4 format "ID filter ID {} not found."
    event HandlerFault($port: string size 40, exception: string size 120) severity warning high id 0x5 format "Handler {} raised {}" throttle 10
    telemetry EventsDropped: U64 id 0x0 update on change
    telemetry HandlerFaults: U32 id 0x1 update on change
  }

  active component FileDownlink {
    time get port timeCaller
    command recv port cmdIn
    command reg port cmdRegOut
    command resp port cmdResponseOut
    event port logOut
    text event port logTextOut
    telemetry port tlmOut
    guarded input port sendFile: Svc.SendFileRequest
    async input port Run: Svc.Sched priority 0 drop
    async input port pingIn: Svc.Ping priority 0 assert
    output port bufferSendOut: Fw.BufferSend
    output port FileComplete: Svc.SendFileComplete
    output port pingOut: Svc.Ping
    async command SendFile(sourceFileName: string size 100, destFileName: string size 100) opcode 0x0 priority 0 assert
    async command Cancel opcode 0x1 priority 0 assert
    async command SendPartial(sourceFileName: string size 100, destFileName: string size 100, startOffset: U32, length: U32) opcode 0x2 priority 0 assert
    event FileOpenError(fileName: string size 100) severity warning high id 0x0 format "Could not open file {}"
    event FileReadError(fileName: string size 100, status: I32) severity warning high id 0x1 format "Could not read file {} with status {}"
    event FileSent(sourceFileName: string size 100, destFileName: string size 100) severity activity high id 0x2 format "Sent file {} to file {}"
    event DownlinkCanceled(sourceFileName: string size 100, destFileName: string size 100) severity activity high id 0x3 format "Canceled downlink of file {} to file {}"
    event DownlinkTimeout(sourceFileName: string size 100, destFileName: string size 100) severity warning high id 0x4 format "Timeout occurred during downlink of file {} to file {}. Downlink has been canceled."
    event DownlinkPartialWarning(startOffset: U32, length: U32, filesize: U32, sourceFileName: string size 100, destFileName: string size 100) severity warning low id 0x5 format "Offset {} plus length {} is greater than source size {} for partial downlink of file {} to file {}. "
    event DownlinkPartialFail(sourceFileName: string size 100, destFileName: string size 100, startOffset: U32, filesize: U32) severity warning high id 0x6 format "Error occurred during partial downlink of file {} to file {}. Offset {} greater than or equal to source filesize {}."
    event SendDataFail(sourceFileName: string size 100, byteOffset: U32) severity warning high id 0x7 format "Failed to send data packet from file {} at byte offset {}."
    event SendStarted(fileSize: U32, sourceFileName: string size 100, destFileName: string size 100) severity activity high id 0x8 format "Downlink of {} bytes started from {} to {}"
    event FileNameTooLong(fileName: string size 100, $size: U32, limit: U32) severity warning high id 0x40 format "File name {} is {} bytes; a file packet carries at most {} bytes"
    event PathRefused(fileName: string size 100, status: I32, reason: string size 40) severity warning high id 0x41 format "File {} refused (Os::File status {}): {}"
    event HandlerFault($port: string size 40, exception: string size 120) severity warning high id 0x42 format "Handler {} raised {}" throttle 10
    telemetry FilesSent: U32 id 0x0 update always
    telemetry PacketsSent: U32 id 0x1 update always
    telemetry Warnings: U32 id 0x2 update always
    telemetry HandlerFaults: U32 id 0x3 update on change
  }

  active component FileManager {
    time get port timeCaller
    command recv port cmdIn
    command reg port cmdRegOut
    command resp port cmdResponseOut
    event port logOut
    text event port logTextOut
    telemetry port tlmOut
    async input port pingIn: Svc.Ping priority 0 assert
    sync input port schedIn: Svc.Sched
    output port pingOut: Svc.Ping
    async command CreateDirectory(dirName: string size 256) opcode 0x0 priority 0 assert
    async command MoveFile(sourceFileName: string size 256, destFileName: string size 256) opcode 0x1 priority 0 assert
    async command RemoveDirectory(dirName: string size 256) opcode 0x2 priority 0 assert
    async command RemoveFile(fileName: string size 256, ignoreErrors: bool) opcode 0x3 priority 0 assert
    async command ShellCommand($command: string size 256, logFileName: string size 256) opcode 0x4 priority 0 assert
    async command AppendFile(source: string size 256, target: string size 256) opcode 0x5 priority 0 assert
    async command FileSize(fileName: string size 256) opcode 0x6 priority 0 assert
    async command ListDirectory(dirName: string size 200) opcode 0x7 priority 0 assert
    async command CalculateCrc(filename: string size 200) opcode 0x8 priority 0 assert
    event DirectoryCreateError(dirName: string size 256, status: U32) severity warning high id 0x0 format "Could not create directory {}, returned status {}"
    event DirectoryRemoveError(dirName: string size 256, status: U32) severity warning high id 0x1 format "Could not remove directory {}, returned status {}"
    event FileMoveError(sourceFileName: string size 256, destFileName: string size 256, status: U32) severity warning high id 0x2 format "Could not move file {} to file {}, returned status {}"
    event FileRemoveError(fileName: string size 256, status: U32) severity warning high id 0x3 format "Could not remove file {}, returned status {}"
    event ShellCommandFailed($command: string size 256, status: U32) severity warning high id 0x4 format "Shell command {} failed with status {}"
    event AppendFileFailed(source: string size 256, target: string size 256, status: U32) severity warning high id 0x5 format "Appending {} onto {} failed with status {}"
    event AppendFileSucceeded(source: string size 256, target: string size 256) severity activity high id 0x6 format "Appended {} to the end of {}"
    event ShellCommandSucceeded($command: string size 256) severity activity high id 0x7 format "Shell command {} succeeded"
    event CreateDirectorySucceeded(dirName: string size 256) severity activity high id 0x8 format "Created directory {} successfully"
    event RemoveDirectorySucceeded(dirName: string size 256) severity activity high id 0x9 format "Removed directory {} successfully"
    event MoveFileSucceeded(sourceFileName: string size 256, destFileName: string size 256) severity activity high id 0xA format "Moved file {} to file {} successfully"
    event RemoveFileSucceeded(fileName: string size 256) severity activity high id 0xB format "Removed file {} successfully"
    event AppendFileStarted(source: string size 256, target: string size 256) severity activity high id 0xC format "Appending file {} to the end of {}..."
    event ShellCommandStarted($command: string size 256) severity activity high id 0xD format "Running shell command {}..."
    event CreateDirectoryStarted(dirName: string size 256) severity activity high id 0xE format "Creating directory {}..."
    event RemoveDirectoryStarted(dirName: string size 256) severity activity high id 0xF format "Removing directory {}..."
    event MoveFileStarted(sourceFileName: string size 256, destFileName: string size 256) severity activity high id 0x10 format "Moving file {} to file {}..."
    event RemoveFileStarted(fileName: string size 256) severity activity high id 0x11 format "Removing file {}..."
    event FileSizeSucceeded(fileName: string size 256, $size: U64) severity activity high id 0x12 format "The size of file {} is {} B"
    event FileSizeError(fileName: string size 256, status: U32) severity warning high id 0x13 format "Failed to get the size of file {}, returned status {}"
    event FileSizeStarted(fileName: string size 256) severity activity high id 0x14 format "Checking size of file {}..."
    event ListDirectoryStarted(dirName: string size 200) severity activity high id 0x15 format "Listing contents of directory {}..."
    event ListDirectorySucceeded(dirName: string size 200, fileCount: U32) severity activity high id 0x16 format "Directory {} contains {} files"
    event ListDirectoryError(dirName: string size 200, status: U32) severity warning high id 0x17 format "Failed to list directory {}, returned status {}"
    event DirectoryListing(dirName: string size 200, fileName: string size 200, fileSize: U64) severity activity high id 0x18 format "Directory {}: {} ({} bytes)"
    event DirectoryListingSubdir(dirName: string size 200, subdirName: string size 200) severity activity high id 0x19 format "Directory {}: {}"
    event CalculateCrcStarted(fileName: string size 200) severity activity high id 0x1A format "Started CRC calculation for file {}"
    event CalculateCrcFailed(fileName: string size 200, status: U32) severity warning high id 0x1B format "Failed CRC calculation for file {}, returned status {}"
    event CalculateCrcSucceeded(fileName: string size 200, crc: U32) severity activity high id 0x1C format "{} has CRC value 0x{x}"
    event FileNameFormatError(fileName: string size 200, status: Fw.StringFormatStatus) severity warning high id 0x1D format "Failed to format full path for file {} with status {}"
    event PathRefused(path: string size 256, reason: string size 40) severity warning high id 0x40 format "Path {} refused: {}"
    event HandlerFault($port: string size 40, exception: string size 120) severity warning high id 0x41 format "Handler {} raised {}" throttle 10
    telemetry CommandsExecuted: U32 id 0x0 update always
    telemetry Errors: U32 id 0x1 update always
    telemetry HandlerFaults: U32 id 0x2 update on change
  }

  active component FileUplink {
    time get port timeCaller
    event port logOut
    text event port logTextOut
    telemetry port tlmOut
    async input port bufferSendIn: Fw.BufferSend priority 0 block
    async input port pingIn: Svc.Ping priority 0 assert
    output port pingOut: Svc.Ping
    output port fileAnnounce: Svc.FileAnnounce
    event BadChecksum(fileName: string size 40, computed: U32, read: U32) severity warning high id 0x0 format "Bad checksum value during receipt of file {}: computed 0x{x}, read 0x{x}"
    event FileOpenError(fileName: string size 40) severity warning high id 0x1 format "Could not open file {}"
    event FileReceived(fileName: string size 40) severity activity high id 0x2 format "Received file {}"
    event FileWriteError(fileName: string size 40) severity warning high id 0x3 format "Could not write to file {}" throttle 5
    event InvalidReceiveMode(packetType: FwPacketDescriptorType, mode: U32) severity warning high id 0x4 format "Packet type {} received in mode {}" throttle 5
    event PacketOutOfBounds(packetIndex: U32, fileName: string size 40) severity warning high id 0x5 format "Packet {} out of bounds for file {}" throttle 5
    event PacketOutOfOrder(packetIndex: U32, lastPacketIndex: U32) severity warning high id 0x6 format "Received packet {} after packet {}" throttle 20
    event PacketDuplicate(packetIndex: U32) severity warning high id 0x7 format "Received a duplicate of packet {}" throttle 20
    event UplinkCanceled severity activity high id 0x8 format "Received CANCEL packet"
    event DecodeError(status: I32) severity warning high id 0x9 format "Unable to decode file packet. Status: {}"
    event InvalidPacketReceived(packetType: FwPacketDescriptorType) severity warning high id 0xA format "Invalid packet received. Wrong packet type: {}"
    event PathRefused(fileName: string size 40, status: I32, reason: string size 40) severity warning high id 0x40 format "File {} refused (Os::File status {}): {}"
    event HandlerFault($port: string size 40, exception: string size 120) severity warning high id 0x41 format "Handler {} raised {}" throttle 10
    telemetry FilesReceived: U32 id 0x0 update always
    telemetry PacketsReceived: U32 id 0x1 update always
    telemetry Warnings: U32 id 0x2 update always
    telemetry FilesReceivedFailed: U32 id 0x3 update always
    telemetry HandlerFaults: U32 id 0x4 update on change
  }

  queued component Health {
    time get port timeCaller
    command recv port cmdIn
    command reg port cmdRegOut
    command resp port cmdResponseOut
    event port logOut
    text event port logTextOut
    telemetry port tlmOut
    sync input port Run: Svc.Sched
    async input port PingReturn: [25] Svc.Ping priority 0 drop
    output port PingSend: [25] Svc.Ping
    output port WdogStroke: Svc.WatchDog
    async command HLTH_ENABLE(enable: Fw.FwEnabled) opcode 0x0 priority 0 assert
    async command HLTH_PING_ENABLE($entry: string size 40, enable: Fw.FwEnabled) opcode 0x1 priority 0 assert
    async command HLTH_CHNG_PING($entry: string size 40, warningValue: U32, fatalValue: U32) opcode 0x2 priority 0 assert
    event HLTH_PING_WARN($entry: string size 40) severity warning high id 0x0 format "Ping entry {} late warning"
    event HLTH_PING_LATE($entry: string size 40) severity fatal id 0x1 format "Ping entry {} did not respond"
    event HLTH_PING_WRONG_KEY($entry: string size 40, badKey: U32) severity fatal id 0x2 format "Ping entry {} responded with wrong key 0x{x}"
    event HLTH_CHECK_ENABLE(enabled: Fw.FwEnabled) severity activity high id 0x3 format "Health checking set to {}"
    event HLTH_CHECK_PING(enabled: Fw.FwEnabled, $entry: string size 40) severity activity high id 0x4 format "Health checking set to {} for {}"
    event HLTH_CHECK_LOOKUP_ERROR($entry: string size 40) severity warning low id 0x5 format "Couldn't find entry {}"
    event HLTH_PING_UPDATED($entry: string size 40, warn: U32, $fatal: U32) severity activity high id 0x6 format "Health ping for {} changed to WARN {} FATAL {}"
    event HLTH_PING_INVALID_VALUES($entry: string size 40, warn: U32, $fatal: U32) severity warning high id 0x7 format "Health ping for {} invalid values: WARN {} FATAL {}"
    event HandlerFault($port: string size 40, exception: string size 120) severity warning high id 0x8 format "Handler {} raised {}" throttle 10
    telemetry PingLateWarnings: U32 id 0x0 update always
    telemetry HandlerFaults: U32 id 0x1 update on change
    match PingSend with PingReturn
  }

  active component PrmDb {
    enum Merge : U8 {
      MERGE = 0
      RESET = 1
    } default MERGE
    enum PrmDbFileLoadState : U8 {
      IDLE = 0
      LOADING_FILE_UPDATES = 1
      FILE_UPDATES_STAGED = 2
    } default IDLE
    enum PrmLoadAction : U8 {
      SET_PARAMETER = 0
      SAVE_FILE_COMMAND = 1
      LOAD_FILE_COMMAND = 2
      COMMIT_STAGED_COMMAND = 3
    } default SET_PARAMETER
    enum PrmReadError : U8 {
      OPEN = 0
      DELIMITER = 1
      DELIMITER_SIZE = 2
      DELIMITER_VALUE = 3
      RECORD_SIZE = 4
      RECORD_SIZE_SIZE = 5
      RECORD_SIZE_VALUE = 6
      PARAMETER_ID = 7
      PARAMETER_ID_SIZE = 8
      PARAMETER_VALUE = 9
      PARAMETER_VALUE_SIZE = 10
      CRC = 11
      CRC_SIZE = 12
      CRC_BUFFER = 13
      SEEK_ZERO = 14
    } default OPEN
    enum PrmWriteError : U8 {
      OPEN = 0
      DELIMITER = 1
      DELIMITER_SIZE = 2
      RECORD_SIZE = 3
      RECORD_SIZE_SIZE = 4
      PARAMETER_ID = 5
      PARAMETER_ID_SIZE = 6
      PARAMETER_VALUE = 7
      PARAMETER_VALUE_SIZE = 8
      CRC_PLACE = 9
      CRC_REAL = 10
      CURR_POSITION = 11
      SEEK_ZERO = 12
      SEEK_POSITION = 13
    } default OPEN
    time get port timeCaller
    command recv port cmdIn
    command reg port cmdRegOut
    command resp port cmdResponseOut
    event port logOut
    text event port logTextOut
    telemetry port tlmOut
    guarded input port getPrm: Fw.PrmGet
    guarded input port setPrm: Fw.PrmSet
    async input port pingIn: Svc.Ping priority 0 assert
    output port pingOut: Svc.Ping
    async command PRM_SAVE_FILE opcode 0x0 priority 0 assert
    async command PRM_LOAD_FILE(fileName: string size 200, merge: Svc.PrmDb.Merge) opcode 0x1 priority 0 assert
    async command PRM_COMMIT_STAGED opcode 0x2 priority 0 assert
    event PrmIdNotFound(Id: U32) severity warning low id 0x0 format "Parameter ID 0x{x} not found" throttle 5
    event PrmIdUpdated(Id: U32) severity activity high id 0x1 format "Parameter ID 0x{x} updated"
    event PrmDbFull(Id: U32) severity warning high id 0x2 format "Parameter DB full when adding ID 0x{x} "
    event PrmIdAdded(Id: U32) severity activity high id 0x3 format "Parameter ID 0x{x} added"
    event PrmFileWriteError(stage: Svc.PrmDb.PrmWriteError, $record: I32, error: I32) severity warning high id 0x4 format "Parameter write failed in stage {} with record {} and error {}"
    event PrmFileSaveComplete(records: U32) severity activity high id 0x5 format "Parameter file save completed. Wrote {} records."
    event PrmFileReadError(stage: Svc.PrmDb.PrmReadError, $record: I32, error: I32) severity warning high id 0x6 format "Parameter file read failed in stage {} with record {} and error {}"
    event PrmFileLoadComplete(databaseString: string size 80, recordsTotal: U32, recordsAdded: U32, recordsUpdated: U32) severity activity high id 0x7 format "Parameter file load completed. Database: {}, Records: {} ({} added and {} updated)."
    event PrmDbCommitComplete severity activity high id 0x8 format "Parameter DB commit complete, staged updates are now active."
    event PrmDbCopyAllComplete(databaseStringSrc: string size 80, databaseStringDest: string size 80) severity activity high id 0x9 format "All parameters copied. Source database: {}, Destination database: {}."
    event PrmDbFileLoadFailed severity warning high id 0xA format "Parameter file load failed. Clearing staging database and abandoning parameter file load."
    event PrmDbFileLoadInvalidAction(currentState: Svc.PrmDb.PrmDbFileLoadState, attemptedAction: Svc.PrmDb.PrmLoadAction) severity warning low id 0xB format "Invalid action during parameter file load. Current state: {}, Action (Invalid for current state): {}."
    event PrmFileBadCrc(readCrc: U32, compCrc: U32) severity warning high id 0xC format "Parameter file failed CRC. Read: 0x{x} Computed: 0x{x}"
    event HandlerFault($port: string size 40, exception: string size 120) severity warning high id 0xD format "Handler {} raised {}" throttle 10
    telemetry HandlerFaults: U32 id 0x0 update on change
  }

  passive component RateGroupDriver {
    time get port timeCaller
    event port logOut
    text event port logTextOut
    telemetry port tlmOut
    sync input port CycleIn: Svc.Cycle
    output port CycleOut: [10] Svc.Cycle
    event HandlerFault($port: string size 40, exception: string size 120) severity warning high id 0x0 format "Handler {} raised {}" throttle 10
    telemetry HandlerFaults: U32 id 0x0 update on change
  }

  active component ActiveRateGroup {
    time get port timeCaller
    event port logOut
    text event port logTextOut
    telemetry port tlmOut
    async input port CycleIn: Svc.Cycle priority 0 drop
    async input port PingIn: Svc.Ping priority 0 assert
    output port RateGroupMemberOut: [25] Svc.Sched
    output port PingOut: Svc.Ping
    event RateGroupStarted severity diagnostic id 0x0 format "Rate group started."
    event RateGroupCycleSlip(cycle: U32) severity warning high id 0x1 format "Rate group cycle slipped on cycle {}" throttle 5
    event RateGroupMemberFault(member: U32, error: string size 80) severity warning high id 0x2 format "Rate group member {} raised: {}" throttle 5
    event HandlerFault($port: string size 40, exception: string size 120) severity warning high id 0x3 format "Handler {} raised {}" throttle 10
    telemetry RgMaxTime: U32 id 0x0 update always format "{} us"
    telemetry RgCycleSlips: U32 id 0x1 update always
    telemetry RgMemberFaults: U32 id 0x2 update always
    telemetry HandlerFaults: U32 id 0x3 update on change
  }

  passive component PassiveTextLogger {
    time get port timeCaller
    event port logOut
    text event port logTextOut
    telemetry port tlmOut
    sync input port TextLogger: Fw.LogText
    event HandlerFault($port: string size 40, exception: string size 120) severity warning high id 0x0 format "Handler {} raised {}" throttle 10
    telemetry HandlerFaults: U32 id 0x0 update on change
  }

  passive component PosixTime {
    time get port timeCaller
    event port logOut
    text event port logTextOut
    telemetry port tlmOut
    sync input port timeGetPort: Fw.Time
    event HandlerFault($port: string size 40, exception: string size 120) severity warning high id 0x0 format "Handler {} raised {}" throttle 10
    telemetry HandlerFaults: U32 id 0x0 update on change
  }

  active component TlmChan {
    time get port timeCaller
    event port logOut
    text event port logTextOut
    telemetry port tlmOut
    sync input port TlmRecv: Fw.Tlm
    guarded input port TlmGet: Fw.TlmGet
    async input port Run: Svc.Sched priority 0 assert
    async input port pingIn: Svc.Ping priority 0 assert
    output port PktSend: Fw.Com
    output port pingOut: Svc.Ping
    event HandlerFault($port: string size 40, exception: string size 120) severity warning high id 0x0 format "Handler {} raised {}" throttle 10
    telemetry HandlerFaults: U32 id 0x0 update on change
  }

  active component TlmPacketizer {
    time get port timeCaller
    command recv port cmdIn
    command reg port cmdRegOut
    command resp port cmdResponseOut
    event port logOut
    text event port logTextOut
    telemetry port tlmOut
    sync input port TlmRecv: Fw.Tlm
    guarded input port TlmGet: Fw.TlmGet
    async input port Run: Svc.Sched priority 0 assert
    async input port pingIn: Svc.Ping priority 0 assert
    output port PktSend: Fw.Com
    output port pingOut: Svc.Ping
    async command SET_LEVEL(level: U32) opcode 0x0 priority 0 assert
    async command SEND_PKT($id: U32) opcode 0x1 priority 0 assert
    event NoChan(Id: U32) severity warning low id 0x0 format "Telemetry ID 0x{x} not packetized"
    event LevelSet($id: U32) severity activity high id 0x1 format "Telemetry send level to {}"
    event MaxLevelExceed(level: U32, max: U32) severity warning low id 0x2 format "Requested send level {} higher than max packet level of {}"
    event PacketSent($id: U32) severity activity low id 0x3 format "Sent packet ID {}"
    event PacketNotFound($id: U32) severity warning low id 0x4 format "Could not find packet ID {}"
    event HandlerFault($port: string size 40, exception: string size 120) severity warning high id 0x5 format "Handler {} raised {}" throttle 10
    telemetry SendLevel: U32 id 0x0 update always
    telemetry HandlerFaults: U32 id 0x1 update on change
  }

  passive component Version {
    time get port timeCaller
    command recv port cmdIn
    command reg port cmdRegOut
    command resp port cmdResponseOut
    event port logOut
    text event port logTextOut
    telemetry port tlmOut
    guarded input port getVersion: Svc.Version
    guarded input port setVersion: Svc.Version
    guarded command ENABLE(enable: Svc.VersionEnabled) opcode 0x0
    guarded command VERSION(version_type: Svc.VersionType) opcode 0x1
    event FrameworkVersion(version: string size 40) severity activity low id 0x0 format "Framework Version: [{}]"
    event ProjectVersion(version: string size 40) severity activity low id 0x1 format "Project Version: [{}]"
    event LibraryVersions(version: string size 40) severity activity low id 0x2 format "Libary Versions: [{}]"
    event CustomVersions(version_enum: Svc.VersionCfg.VersionEnum, version_value: string size 40) severity activity low id 0x3 format "Custom Versions: [{}] [{}]"
    event HandlerFault($port: string size 40, exception: string size 120) severity warning high id 0x4 format "Handler {} raised {}" throttle 10
    telemetry FrameworkVersion: string size 40 id 0x0 update always
    telemetry ProjectVersion: string size 40 id 0x1 update always
    telemetry CustomVersion01: Svc.CustomVersionDb id 0x2 update always
    telemetry CustomVersion02: Svc.CustomVersionDb id 0x3 update always
    telemetry CustomVersion03: Svc.CustomVersionDb id 0x4 update always
    telemetry CustomVersion04: Svc.CustomVersionDb id 0x5 update always
    telemetry CustomVersion05: Svc.CustomVersionDb id 0x6 update always
    telemetry CustomVersion06: Svc.CustomVersionDb id 0x7 update always
    telemetry CustomVersion07: Svc.CustomVersionDb id 0x8 update always
    telemetry CustomVersion08: Svc.CustomVersionDb id 0x9 update always
    telemetry CustomVersion09: Svc.CustomVersionDb id 0xA update always
    telemetry CustomVersion10: Svc.CustomVersionDb id 0xB update always
    telemetry LibraryVersion01: string size 40 id 0xC update always
    telemetry LibraryVersion02: string size 40 id 0xD update always
    telemetry LibraryVersion03: string size 40 id 0xE update always
    telemetry LibraryVersion04: string size 40 id 0xF update always
    telemetry LibraryVersion05: string size 40 id 0x10 update always
    telemetry LibraryVersion06: string size 40 id 0x11 update always
    telemetry LibraryVersion07: string size 40 id 0x12 update always
    telemetry LibraryVersion08: string size 40 id 0x13 update always
    telemetry LibraryVersion09: string size 40 id 0x14 update always
    telemetry LibraryVersion10: string size 40 id 0x15 update always
    telemetry HandlerFaults: U32 id 0x16 update on change
  }
}

module Svc {
  module VersionCfg {
    enum VersionEnum : U32 {
      PROJECT_VERSION_00 = 0
      PROJECT_VERSION_01 = 1
      PROJECT_VERSION_02 = 2
      PROJECT_VERSION_03 = 3
      PROJECT_VERSION_04 = 4
      PROJECT_VERSION_05 = 5
      PROJECT_VERSION_06 = 6
      PROJECT_VERSION_07 = 7
      PROJECT_VERSION_08 = 8
      PROJECT_VERSION_09 = 9
    } default PROJECT_VERSION_00
  }
}
