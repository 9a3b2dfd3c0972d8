# Written by fprime-lite (python -m fprime_lite.deploy.fpp.export deployments/coursework/topology.yaml) from deployments/coursework/topology.yaml.
# Regenerate it rather than edit it; tests/fprime_lite/deploy/test_fpp.py checks it is current.

module CdhCore {
  instance cmdDisp: Svc.CommandDispatcher base id 0x01000100 queue size 10

  instance events: Svc.EventManager base id 0x01000200 queue size 10

  instance $health: Svc.Health base id 0x01000300 queue size 25

  instance version: Svc.Version base id 0x01000400

  instance textLogger: Svc.PassiveTextLogger base id 0x01000500

  instance tlmSend: Svc.TlmChan base id 0x01006000 queue size 10
}

module CourseworkDeployment {
  instance rateGroupDriver: Svc.RateGroupDriver base id 0x10000000

  instance rateGroup100Hz: Svc.ActiveRateGroup base id 0x10001000 queue size 10

  instance rateGroup10Hz: Svc.ActiveRateGroup base id 0x10002000 queue size 10

  instance rateGroup1Hz: Svc.ActiveRateGroup base id 0x10003000 queue size 10

  instance chronoTime: Svc.PosixTime base id 0x10004000

  instance cmdSeq: Svc.CmdSequencer base id 0x10006000 queue size 10

  instance imuManager: Components.ImuManager base id 0x10017000

  instance starTracker: Components.StarTracker base id 0x10070000

  instance orbitEphemeris: Components.OrbitEphemeris base id 0x10071000

  instance torqueRods: Components.TorqueRodDriver base id 0x10072000

  instance wheelX: Components.ReactionWheelDriver base id 0x10073000

  instance wheelY: Components.ReactionWheelDriver base id 0x10074000

  instance wheelZ: Components.ReactionWheelDriver base id 0x10075000

  instance controller: Components.CourseworkController base id 0x10076000

  topology CourseworkDeployment {
    instance CdhCore.cmdDisp
    instance CdhCore.events
    instance CdhCore.$health
    instance CdhCore.version
    instance CdhCore.textLogger
    instance CdhCore.tlmSend
    instance FileHandling.fileUplink
    instance FileHandling.fileDownlink
    instance FileHandling.fileManager
    instance FileHandling.prmDb
    instance rateGroupDriver
    instance rateGroup100Hz
    instance rateGroup10Hz
    instance rateGroup1Hz
    instance chronoTime
    instance cmdSeq
    instance imuManager
    instance starTracker
    instance orbitEphemeris
    instance torqueRods
    instance wheelX
    instance wheelY
    instance wheelZ
    instance controller
    connections Sequencer {
      cmdSeq.comCmdOut[0] -> CdhCore.cmdDisp.seqCmdBuff[0]
      CdhCore.cmdDisp.seqCmdStatus[0] -> cmdSeq.cmdResponseIn[0]
    }
    connections Control {
      controller.magneticFieldGet[0] -> imuManager.magneticFieldGet[0]
      controller.angularVelocityGet[0] -> imuManager.angularVelocityGet[0]
      controller.attitudeGet[0] -> starTracker.attitudeGet[0]
      controller.orbitFrameGet[0] -> orbitEphemeris.orbitFrameGet[0]
      controller.dipoleSet[0] -> torqueRods.dipoleSet[0]
      controller.wheelStateGet[0] -> wheelX.wheelStateGet[0]
      controller.wheelStateGet[1] -> wheelY.wheelStateGet[0]
      controller.wheelStateGet[2] -> wheelZ.wheelStateGet[0]
      controller.wheelTorqueSet[0] -> wheelX.torqueSet[0]
      controller.wheelTorqueSet[1] -> wheelY.torqueSet[0]
      controller.wheelTorqueSet[2] -> wheelZ.torqueSet[0]
    }
    connections RateGroups {
      rateGroupDriver.CycleOut[0] -> rateGroup100Hz.CycleIn[0]
      rateGroup100Hz.RateGroupMemberOut[0] -> controller.run[0]
      rateGroupDriver.CycleOut[1] -> rateGroup10Hz.CycleIn[0]
      rateGroup10Hz.RateGroupMemberOut[0] -> cmdSeq.schedIn[0]
      rateGroupDriver.CycleOut[2] -> rateGroup1Hz.CycleIn[0]
      rateGroup1Hz.RateGroupMemberOut[0] -> imuManager.run[0]
      rateGroup1Hz.RateGroupMemberOut[1] -> starTracker.run[0]
      rateGroup1Hz.RateGroupMemberOut[2] -> wheelX.run[0]
      rateGroup1Hz.RateGroupMemberOut[3] -> wheelY.run[0]
      rateGroup1Hz.RateGroupMemberOut[4] -> wheelZ.run[0]
      rateGroup1Hz.RateGroupMemberOut[5] -> CdhCore.tlmSend.Run[0]
      rateGroup1Hz.RateGroupMemberOut[6] -> CdhCore.$health.Run[0]
      rateGroup1Hz.RateGroupMemberOut[7] -> FileHandling.fileDownlink.Run[0]
    }
    connections Pattern_command {
      CdhCore.cmdDisp.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[0]
      CdhCore.cmdDisp.compCmdSend[0] -> CdhCore.cmdDisp.cmdIn[0]
      CdhCore.cmdDisp.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      CdhCore.events.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[1]
      CdhCore.cmdDisp.compCmdSend[1] -> CdhCore.events.cmdIn[0]
      CdhCore.events.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      CdhCore.$health.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[2]
      CdhCore.cmdDisp.compCmdSend[2] -> CdhCore.$health.cmdIn[0]
      CdhCore.$health.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      CdhCore.version.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[3]
      CdhCore.cmdDisp.compCmdSend[3] -> CdhCore.version.cmdIn[0]
      CdhCore.version.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      FileHandling.fileDownlink.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[4]
      CdhCore.cmdDisp.compCmdSend[4] -> FileHandling.fileDownlink.cmdIn[0]
      FileHandling.fileDownlink.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      FileHandling.fileManager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[5]
      CdhCore.cmdDisp.compCmdSend[5] -> FileHandling.fileManager.cmdIn[0]
      FileHandling.fileManager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      FileHandling.prmDb.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[6]
      CdhCore.cmdDisp.compCmdSend[6] -> FileHandling.prmDb.cmdIn[0]
      FileHandling.prmDb.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      cmdSeq.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[7]
      CdhCore.cmdDisp.compCmdSend[7] -> cmdSeq.cmdIn[0]
      cmdSeq.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      imuManager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[8]
      CdhCore.cmdDisp.compCmdSend[8] -> imuManager.cmdIn[0]
      imuManager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      starTracker.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[9]
      CdhCore.cmdDisp.compCmdSend[9] -> starTracker.cmdIn[0]
      starTracker.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      torqueRods.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[10]
      CdhCore.cmdDisp.compCmdSend[10] -> torqueRods.cmdIn[0]
      torqueRods.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      wheelX.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[11]
      CdhCore.cmdDisp.compCmdSend[11] -> wheelX.cmdIn[0]
      wheelX.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      wheelY.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[12]
      CdhCore.cmdDisp.compCmdSend[12] -> wheelY.cmdIn[0]
      wheelY.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      wheelZ.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[13]
      CdhCore.cmdDisp.compCmdSend[13] -> wheelZ.cmdIn[0]
      wheelZ.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      controller.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[14]
      CdhCore.cmdDisp.compCmdSend[14] -> controller.cmdIn[0]
      controller.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
    }
    connections Pattern_event {
      CdhCore.cmdDisp.logOut[0] -> CdhCore.events.LogRecv[0]
      CdhCore.events.logOut[0] -> CdhCore.events.LogRecv[0]
      CdhCore.$health.logOut[0] -> CdhCore.events.LogRecv[0]
      CdhCore.version.logOut[0] -> CdhCore.events.LogRecv[0]
      CdhCore.textLogger.logOut[0] -> CdhCore.events.LogRecv[0]
      CdhCore.tlmSend.logOut[0] -> CdhCore.events.LogRecv[0]
      FileHandling.fileUplink.logOut[0] -> CdhCore.events.LogRecv[0]
      FileHandling.fileDownlink.logOut[0] -> CdhCore.events.LogRecv[0]
      FileHandling.fileManager.logOut[0] -> CdhCore.events.LogRecv[0]
      FileHandling.prmDb.logOut[0] -> CdhCore.events.LogRecv[0]
      rateGroupDriver.logOut[0] -> CdhCore.events.LogRecv[0]
      rateGroup100Hz.logOut[0] -> CdhCore.events.LogRecv[0]
      rateGroup10Hz.logOut[0] -> CdhCore.events.LogRecv[0]
      rateGroup1Hz.logOut[0] -> CdhCore.events.LogRecv[0]
      chronoTime.logOut[0] -> CdhCore.events.LogRecv[0]
      cmdSeq.logOut[0] -> CdhCore.events.LogRecv[0]
      imuManager.logOut[0] -> CdhCore.events.LogRecv[0]
      starTracker.logOut[0] -> CdhCore.events.LogRecv[0]
      orbitEphemeris.logOut[0] -> CdhCore.events.LogRecv[0]
      torqueRods.logOut[0] -> CdhCore.events.LogRecv[0]
      wheelX.logOut[0] -> CdhCore.events.LogRecv[0]
      wheelY.logOut[0] -> CdhCore.events.LogRecv[0]
      wheelZ.logOut[0] -> CdhCore.events.LogRecv[0]
      controller.logOut[0] -> CdhCore.events.LogRecv[0]
    }
    connections Pattern_telemetry {
      CdhCore.cmdDisp.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      CdhCore.events.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      CdhCore.$health.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      CdhCore.version.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      CdhCore.textLogger.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      CdhCore.tlmSend.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      FileHandling.fileUplink.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      FileHandling.fileDownlink.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      FileHandling.fileManager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      FileHandling.prmDb.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      rateGroupDriver.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      rateGroup100Hz.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      rateGroup10Hz.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      rateGroup1Hz.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      chronoTime.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      cmdSeq.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      imuManager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      starTracker.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      orbitEphemeris.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      torqueRods.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      wheelX.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      wheelY.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      wheelZ.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      controller.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
    }
    connections Pattern_param {
      imuManager.prmGetOut[0] -> FileHandling.prmDb.getPrm[0]
      imuManager.prmSetOut[0] -> FileHandling.prmDb.setPrm[0]
      controller.prmGetOut[0] -> FileHandling.prmDb.getPrm[0]
      controller.prmSetOut[0] -> FileHandling.prmDb.setPrm[0]
    }
    connections Pattern_health {
      CdhCore.$health.PingSend[0] -> CdhCore.cmdDisp.pingIn[0]
      CdhCore.cmdDisp.pingOut[0] -> CdhCore.$health.PingReturn[0]
      CdhCore.$health.PingSend[1] -> CdhCore.events.pingIn[0]
      CdhCore.events.pingOut[0] -> CdhCore.$health.PingReturn[1]
      CdhCore.$health.PingSend[2] -> CdhCore.tlmSend.pingIn[0]
      CdhCore.tlmSend.pingOut[0] -> CdhCore.$health.PingReturn[2]
      CdhCore.$health.PingSend[3] -> FileHandling.fileUplink.pingIn[0]
      FileHandling.fileUplink.pingOut[0] -> CdhCore.$health.PingReturn[3]
      CdhCore.$health.PingSend[4] -> FileHandling.fileDownlink.pingIn[0]
      FileHandling.fileDownlink.pingOut[0] -> CdhCore.$health.PingReturn[4]
      CdhCore.$health.PingSend[5] -> FileHandling.fileManager.pingIn[0]
      FileHandling.fileManager.pingOut[0] -> CdhCore.$health.PingReturn[5]
      CdhCore.$health.PingSend[6] -> FileHandling.prmDb.pingIn[0]
      FileHandling.prmDb.pingOut[0] -> CdhCore.$health.PingReturn[6]
      CdhCore.$health.PingSend[7] -> rateGroup100Hz.PingIn[0]
      rateGroup100Hz.PingOut[0] -> CdhCore.$health.PingReturn[7]
      CdhCore.$health.PingSend[8] -> rateGroup10Hz.PingIn[0]
      rateGroup10Hz.PingOut[0] -> CdhCore.$health.PingReturn[8]
      CdhCore.$health.PingSend[9] -> rateGroup1Hz.PingIn[0]
      rateGroup1Hz.PingOut[0] -> CdhCore.$health.PingReturn[9]
      CdhCore.$health.PingSend[10] -> cmdSeq.pingIn[0]
      cmdSeq.pingOut[0] -> CdhCore.$health.PingReturn[10]
    }
    connections Pattern_time {
      CdhCore.cmdDisp.timeCaller[0] -> chronoTime.timeGetPort[0]
      CdhCore.events.timeCaller[0] -> chronoTime.timeGetPort[0]
      CdhCore.$health.timeCaller[0] -> chronoTime.timeGetPort[0]
      CdhCore.version.timeCaller[0] -> chronoTime.timeGetPort[0]
      CdhCore.textLogger.timeCaller[0] -> chronoTime.timeGetPort[0]
      CdhCore.tlmSend.timeCaller[0] -> chronoTime.timeGetPort[0]
      FileHandling.fileUplink.timeCaller[0] -> chronoTime.timeGetPort[0]
      FileHandling.fileDownlink.timeCaller[0] -> chronoTime.timeGetPort[0]
      FileHandling.fileManager.timeCaller[0] -> chronoTime.timeGetPort[0]
      FileHandling.prmDb.timeCaller[0] -> chronoTime.timeGetPort[0]
      rateGroupDriver.timeCaller[0] -> chronoTime.timeGetPort[0]
      rateGroup100Hz.timeCaller[0] -> chronoTime.timeGetPort[0]
      rateGroup10Hz.timeCaller[0] -> chronoTime.timeGetPort[0]
      rateGroup1Hz.timeCaller[0] -> chronoTime.timeGetPort[0]
      chronoTime.timeCaller[0] -> chronoTime.timeGetPort[0]
      cmdSeq.timeCaller[0] -> chronoTime.timeGetPort[0]
      imuManager.timeCaller[0] -> chronoTime.timeGetPort[0]
      starTracker.timeCaller[0] -> chronoTime.timeGetPort[0]
      orbitEphemeris.timeCaller[0] -> chronoTime.timeGetPort[0]
      torqueRods.timeCaller[0] -> chronoTime.timeGetPort[0]
      wheelX.timeCaller[0] -> chronoTime.timeGetPort[0]
      wheelY.timeCaller[0] -> chronoTime.timeGetPort[0]
      wheelZ.timeCaller[0] -> chronoTime.timeGetPort[0]
      controller.timeCaller[0] -> chronoTime.timeGetPort[0]
    }
  }
}

module FileHandling {
  instance fileUplink: Svc.FileUplink base id 0x05000100 queue size 30

  instance fileDownlink: Svc.FileDownlink base id 0x05000200 queue size 30

  instance fileManager: Svc.FileManager base id 0x05000300 queue size 10

  instance prmDb: Svc.PrmDb base id 0x05000400 queue size 10
}
