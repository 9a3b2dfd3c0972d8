# Written by fprime-lite (python -m fprime_lite.deploy.fpp.export deployments/proves_ref/topology_packetized.yaml) from deployments/proves_ref/topology_packetized.yaml.
# Regenerate it rather than edit it; tests/fprime_lite/deploy/test_fpp.py checks it is current.

module CdhCore {
  instance cmdDisp: Svc.CommandDispatcher base id 0x01000100 queue size 10

  instance events: Svc.EventManager base id 0x01000200 queue size 10

  instance $health: Svc.Health base id 0x01000300 queue size 25

  instance version: Svc.Version base id 0x01000400

  instance textLogger: Svc.PassiveTextLogger base id 0x01000500

  instance tlmSend: Svc.TlmPacketizer base id 0x01006000 queue size 10
}

module ComCcsdsUart {
  instance tcSecurityDeframer: Components.TcSecurityDeframer base id 0x2100B000
}

module FileHandling {
  instance fileUplink: Svc.FileUplink base id 0x05000100 queue size 30

  instance fileDownlink: Svc.FileDownlink base id 0x05000200 queue size 30

  instance fileManager: Svc.FileManager base id 0x05000300 queue size 10

  instance prmDb: Svc.PrmDb base id 0x05000400 queue size 10
}

module ReferenceDeployment {
  instance rateGroupDriver: Svc.RateGroupDriver base id 0x10000000

  instance rateGroup50Hz: Svc.ActiveRateGroup base id 0x10001000 queue size 10

  instance rateGroup10Hz: Svc.ActiveRateGroup base id 0x10002000 queue size 10

  instance rateGroup1Hz: Svc.ActiveRateGroup base id 0x10003000 queue size 10

  instance chronoTime: Svc.PosixTime base id 0x10004000

  instance cmdSeq: Svc.CmdSequencer base id 0x10006000 queue size 10

  instance modeManager: Components.ModeManager base id 0x1000A000

  instance imuManager: Components.ImuManager base id 0x10017000

  instance drv2605Face0Manager: Components.MagnetorquerDriver base id 0x10055000

  instance drv2605Face1Manager: Components.MagnetorquerDriver base id 0x10056000

  instance drv2605Face2Manager: Components.MagnetorquerDriver base id 0x10057000

  instance drv2605Face3Manager: Components.MagnetorquerDriver base id 0x10058000

  instance drv2605Face5Manager: Components.MagnetorquerDriver base id 0x10059000

  instance detumbleManager: Components.DetumbleManager base id 0x1005A000

  instance face4LoadSwitch: Components.LoadSwitch base id 0x1002F000

  instance face0LoadSwitch: Components.LoadSwitch base id 0x10030000

  instance face1LoadSwitch: Components.LoadSwitch base id 0x10031000

  instance face2LoadSwitch: Components.LoadSwitch base id 0x10032000

  instance face3LoadSwitch: Components.LoadSwitch base id 0x10033000

  instance face5LoadSwitch: Components.LoadSwitch base id 0x10034000

  instance payloadPowerLoadSwitch: Components.LoadSwitch base id 0x10035000

  instance payloadBatteryLoadSwitch: Components.LoadSwitch base id 0x10036000

  instance watchdog: Components.Watchdog base id 0x10015000

  instance rtcManager: Components.RtcManager base id 0x10016000

  instance resetManager: Components.ResetManager base id 0x10037000

  instance startupManager: Components.StartupManager base id 0x1003B000

  instance powerMonitor: Components.PowerMonitor base id 0x10038000

  instance ina219SysManager: Components.Ina219Manager base id 0x10039000

  instance ina219SolManager: Components.Ina219Manager base id 0x1003A000

  instance payloadSeq: Svc.CmdSequencer base id 0x10062000 queue size 10

  instance burnwire: Components.Burnwire base id 0x1001B000

  instance antennaDeployer: Components.AntennaDeployer base id 0x10022000

  instance downlinkDelay: Components.ComDelay base id 0x1001E000

  instance lora: Components.LoRa base id 0x1001F000

  instance fsFormat: Components.FsFormat base id 0x10078000

  instance picoTempManager: Components.PicoTempManager base id 0x10079000

  instance tmp112Face0Manager: Components.Tmp112Manager base id 0x10042000

  instance tmp112Face1Manager: Components.Tmp112Manager base id 0x10043000

  instance tmp112Face2Manager: Components.Tmp112Manager base id 0x10044000

  instance tmp112Face3Manager: Components.Tmp112Manager base id 0x10045000

  instance tmp112Face4Manager: Components.Tmp112Manager base id 0x10046000

  instance tmp112Face5Manager: Components.Tmp112Manager base id 0x10047000

  instance tmp112BattCell1Manager: Components.Tmp112Manager base id 0x10048000

  instance tmp112BattCell2Manager: Components.Tmp112Manager base id 0x10049000

  instance tmp112BattCell3Manager: Components.Tmp112Manager base id 0x1004A000

  instance tmp112BattCell4Manager: Components.Tmp112Manager base id 0x1004B000

  instance veml6031Face0Manager: Components.Veml6031Manager base id 0x1004D000

  instance veml6031Face1Manager: Components.Veml6031Manager base id 0x1004E000

  instance veml6031Face2Manager: Components.Veml6031Manager base id 0x1004F000

  instance veml6031Face3Manager: Components.Veml6031Manager base id 0x10050000

  instance veml6031Face4Manager: Components.Veml6031Manager base id 0x10051000

  instance veml6031Face5Manager: Components.Veml6031Manager base id 0x10052000

  instance cameraHandler: Components.CameraHandler base id 0x1002B000

  instance thermalManager: Components.ThermalManager base id 0x10041000

  deployment topology ReferenceDeployment {
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
    instance rateGroup50Hz
    instance rateGroup10Hz
    instance rateGroup1Hz
    instance chronoTime
    instance cmdSeq
    instance modeManager
    instance imuManager
    instance drv2605Face0Manager
    instance drv2605Face1Manager
    instance drv2605Face2Manager
    instance drv2605Face3Manager
    instance drv2605Face5Manager
    instance detumbleManager
    instance face4LoadSwitch
    instance face0LoadSwitch
    instance face1LoadSwitch
    instance face2LoadSwitch
    instance face3LoadSwitch
    instance face5LoadSwitch
    instance payloadPowerLoadSwitch
    instance payloadBatteryLoadSwitch
    instance watchdog
    instance rtcManager
    instance resetManager
    instance startupManager
    instance powerMonitor
    instance ina219SysManager
    instance ina219SolManager
    instance payloadSeq
    instance burnwire
    instance antennaDeployer
    instance downlinkDelay
    instance lora
    instance fsFormat
    instance picoTempManager
    instance tmp112Face0Manager
    instance tmp112Face1Manager
    instance tmp112Face2Manager
    instance tmp112Face3Manager
    instance tmp112Face4Manager
    instance tmp112Face5Manager
    instance tmp112BattCell1Manager
    instance tmp112BattCell2Manager
    instance tmp112BattCell3Manager
    instance tmp112BattCell4Manager
    instance veml6031Face0Manager
    instance veml6031Face1Manager
    instance veml6031Face2Manager
    instance veml6031Face3Manager
    instance veml6031Face4Manager
    instance veml6031Face5Manager
    instance cameraHandler
    instance thermalManager
    instance ComCcsdsUart.tcSecurityDeframer
    connections Sequencer {
      cmdSeq.comCmdOut[0] -> CdhCore.cmdDisp.seqCmdBuff[0]
      CdhCore.cmdDisp.seqCmdStatus[0] -> cmdSeq.cmdResponseIn[0]
      cmdSeq.seqStartOut[0] -> startupManager.sequenceStarted[0]
      cmdSeq.seqDone[0] -> startupManager.completeSequence[0]
      payloadSeq.comCmdOut[0] -> CdhCore.cmdDisp.seqCmdBuff[2]
      CdhCore.cmdDisp.seqCmdStatus[2] -> payloadSeq.cmdResponseIn[0]
      rtcManager.cancelSequences[0] -> cmdSeq.seqCancelIn[0]
      rtcManager.cancelSequences[1] -> payloadSeq.seqCancelIn[0]
    }
    connections Antenna {
      antennaDeployer.burnStart[0] -> burnwire.burnStart[0]
      antennaDeployer.burnStop[0] -> burnwire.burnStop[0]
    }
    connections Thermal {
      thermalManager.faceTempGet[0] -> tmp112Face0Manager.temperatureGet[0]
      thermalManager.faceTempGet[1] -> tmp112Face1Manager.temperatureGet[0]
      thermalManager.faceTempGet[2] -> tmp112Face2Manager.temperatureGet[0]
      thermalManager.faceTempGet[3] -> tmp112Face3Manager.temperatureGet[0]
      thermalManager.faceTempGet[4] -> tmp112Face5Manager.temperatureGet[0]
      thermalManager.battCellTempGet[0] -> tmp112BattCell1Manager.temperatureGet[0]
      thermalManager.battCellTempGet[1] -> tmp112BattCell2Manager.temperatureGet[0]
      thermalManager.battCellTempGet[2] -> tmp112BattCell3Manager.temperatureGet[0]
      thermalManager.battCellTempGet[3] -> tmp112BattCell4Manager.temperatureGet[0]
      thermalManager.picoTempGet[0] -> picoTempManager.picoTemperatureGet[0]
    }
    connections Radio {
      downlinkDelay.comStatusOut[0] -> lora.comStatusIn[0]
      lora.comStatusOut[0] -> downlinkDelay.comStatusIn[0]
    }
    connections Detumble {
      detumbleManager.angularVelocityMagnitudeGet[0] -> imuManager.angularVelocityMagnitudeGet[0]
      detumbleManager.magneticFieldGet[0] -> imuManager.magneticFieldGet[0]
      detumbleManager.magneticFieldSamplingPeriodGet[0] -> imuManager.magneticFieldSamplingPeriodGet[0]
      detumbleManager.getSystemMode[0] -> modeManager.getMode[0]
      modeManager.modeChanged[0] -> detumbleManager.systemModeChanged[0]
      detumbleManager.xPlusStart[0] -> drv2605Face0Manager.start[0]
      detumbleManager.xPlusStop[0] -> drv2605Face0Manager.stop[0]
      detumbleManager.xMinusStart[0] -> drv2605Face1Manager.start[0]
      detumbleManager.xMinusStop[0] -> drv2605Face1Manager.stop[0]
      detumbleManager.yPlusStart[0] -> drv2605Face2Manager.start[0]
      detumbleManager.yPlusStop[0] -> drv2605Face2Manager.stop[0]
      detumbleManager.yMinusStart[0] -> drv2605Face3Manager.start[0]
      detumbleManager.yMinusStop[0] -> drv2605Face3Manager.stop[0]
      detumbleManager.zMinusStart[0] -> drv2605Face5Manager.start[0]
      detumbleManager.zMinusStop[0] -> drv2605Face5Manager.stop[0]
    }
    connections ModeManager {
      resetManager.prepareForReboot[0] -> modeManager.prepareForReboot[0]
      watchdog.prepareForReboot[0] -> modeManager.prepareForReboot[0]
      modeManager.stopWatchdog[0] -> watchdog.stop[0]
      modeManager.voltageGet[0] -> ina219SysManager.voltageGet[0]
      modeManager.loadSwitchTurnOff[0] -> face4LoadSwitch.turnOff[0]
      modeManager.loadSwitchTurnOff[1] -> face0LoadSwitch.turnOff[0]
      modeManager.loadSwitchTurnOff[2] -> face1LoadSwitch.turnOff[0]
      modeManager.loadSwitchTurnOff[3] -> face2LoadSwitch.turnOff[0]
      modeManager.loadSwitchTurnOff[4] -> face3LoadSwitch.turnOff[0]
      modeManager.loadSwitchTurnOff[5] -> face5LoadSwitch.turnOff[0]
      modeManager.loadSwitchTurnOff[6] -> payloadPowerLoadSwitch.turnOff[0]
      modeManager.loadSwitchTurnOff[7] -> payloadBatteryLoadSwitch.turnOff[0]
      modeManager.loadSwitchTurnOn[0] -> face4LoadSwitch.turnOn[0]
      modeManager.loadSwitchTurnOn[1] -> face0LoadSwitch.turnOn[0]
      modeManager.loadSwitchTurnOn[2] -> face1LoadSwitch.turnOn[0]
      modeManager.loadSwitchTurnOn[3] -> face2LoadSwitch.turnOn[0]
      modeManager.loadSwitchTurnOn[4] -> face3LoadSwitch.turnOn[0]
      modeManager.loadSwitchTurnOn[5] -> face5LoadSwitch.turnOn[0]
    }
    connections LoadSwitches {
      face0LoadSwitch.loadSwitchStateChanged[0] -> tmp112Face0Manager.loadSwitchStateChanged[0]
      face1LoadSwitch.loadSwitchStateChanged[0] -> tmp112Face1Manager.loadSwitchStateChanged[0]
      face2LoadSwitch.loadSwitchStateChanged[0] -> tmp112Face2Manager.loadSwitchStateChanged[0]
      face3LoadSwitch.loadSwitchStateChanged[0] -> tmp112Face3Manager.loadSwitchStateChanged[0]
      face4LoadSwitch.loadSwitchStateChanged[0] -> tmp112Face4Manager.loadSwitchStateChanged[0]
      face5LoadSwitch.loadSwitchStateChanged[0] -> tmp112Face5Manager.loadSwitchStateChanged[0]
      face0LoadSwitch.loadSwitchStateChanged[1] -> veml6031Face0Manager.loadSwitchStateChanged[0]
      face1LoadSwitch.loadSwitchStateChanged[1] -> veml6031Face1Manager.loadSwitchStateChanged[0]
      face2LoadSwitch.loadSwitchStateChanged[1] -> veml6031Face2Manager.loadSwitchStateChanged[0]
      face3LoadSwitch.loadSwitchStateChanged[1] -> veml6031Face3Manager.loadSwitchStateChanged[0]
      face4LoadSwitch.loadSwitchStateChanged[1] -> veml6031Face4Manager.loadSwitchStateChanged[0]
      face5LoadSwitch.loadSwitchStateChanged[1] -> veml6031Face5Manager.loadSwitchStateChanged[0]
      face0LoadSwitch.loadSwitchStateChanged[2] -> drv2605Face0Manager.loadSwitchStateChanged[0]
      face1LoadSwitch.loadSwitchStateChanged[2] -> drv2605Face1Manager.loadSwitchStateChanged[0]
      face2LoadSwitch.loadSwitchStateChanged[2] -> drv2605Face2Manager.loadSwitchStateChanged[0]
      face3LoadSwitch.loadSwitchStateChanged[2] -> drv2605Face3Manager.loadSwitchStateChanged[0]
      face5LoadSwitch.loadSwitchStateChanged[2] -> drv2605Face5Manager.loadSwitchStateChanged[0]
    }
    connections sysPowerMonitor {
      powerMonitor.sysVoltageGet[0] -> ina219SysManager.voltageGet[0]
      powerMonitor.sysCurrentGet[0] -> ina219SysManager.currentGet[0]
      powerMonitor.sysPowerGet[0] -> ina219SysManager.powerGet[0]
      powerMonitor.solVoltageGet[0] -> ina219SolManager.voltageGet[0]
      powerMonitor.solCurrentGet[0] -> ina219SolManager.currentGet[0]
      powerMonitor.solPowerGet[0] -> ina219SolManager.powerGet[0]
    }
    connections RateGroups {
      rateGroupDriver.CycleOut[0] -> rateGroup50Hz.CycleIn[0]
      rateGroup50Hz.RateGroupMemberOut[0] -> detumbleManager.run[0]
      rateGroupDriver.CycleOut[1] -> rateGroup10Hz.CycleIn[0]
      rateGroup10Hz.RateGroupMemberOut[0] -> cmdSeq.schedIn[0]
      rateGroup10Hz.RateGroupMemberOut[1] -> payloadSeq.schedIn[0]
      rateGroup10Hz.RateGroupMemberOut[2] -> cameraHandler.schedIn[0]
      rateGroup10Hz.RateGroupMemberOut[3] -> downlinkDelay.run[0]
      rateGroupDriver.CycleOut[2] -> rateGroup1Hz.CycleIn[0]
      rateGroup1Hz.RateGroupMemberOut[0] -> watchdog.run[0]
      rateGroup1Hz.RateGroupMemberOut[1] -> imuManager.run[0]
      rateGroup1Hz.RateGroupMemberOut[2] -> startupManager.run[0]
      rateGroup1Hz.RateGroupMemberOut[3] -> powerMonitor.run[0]
      rateGroup1Hz.RateGroupMemberOut[4] -> modeManager.run[0]
      rateGroup1Hz.RateGroupMemberOut[5] -> burnwire.schedIn[0]
      rateGroup1Hz.RateGroupMemberOut[6] -> antennaDeployer.schedIn[0]
      rateGroup1Hz.RateGroupMemberOut[7] -> thermalManager.run[0]
      rateGroup1Hz.RateGroupMemberOut[8] -> CdhCore.tlmSend.Run[0]
      rateGroup1Hz.RateGroupMemberOut[9] -> CdhCore.$health.Run[0]
      rateGroup1Hz.RateGroupMemberOut[10] -> FileHandling.fileDownlink.Run[0]
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
      CdhCore.tlmSend.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[4]
      CdhCore.cmdDisp.compCmdSend[4] -> CdhCore.tlmSend.cmdIn[0]
      CdhCore.tlmSend.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      FileHandling.fileDownlink.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[5]
      CdhCore.cmdDisp.compCmdSend[5] -> FileHandling.fileDownlink.cmdIn[0]
      FileHandling.fileDownlink.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      FileHandling.fileManager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[6]
      CdhCore.cmdDisp.compCmdSend[6] -> FileHandling.fileManager.cmdIn[0]
      FileHandling.fileManager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      FileHandling.prmDb.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[7]
      CdhCore.cmdDisp.compCmdSend[7] -> FileHandling.prmDb.cmdIn[0]
      FileHandling.prmDb.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      cmdSeq.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[8]
      CdhCore.cmdDisp.compCmdSend[8] -> cmdSeq.cmdIn[0]
      cmdSeq.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      modeManager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[9]
      CdhCore.cmdDisp.compCmdSend[9] -> modeManager.cmdIn[0]
      modeManager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      imuManager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[10]
      CdhCore.cmdDisp.compCmdSend[10] -> imuManager.cmdIn[0]
      imuManager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      drv2605Face0Manager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[11]
      CdhCore.cmdDisp.compCmdSend[11] -> drv2605Face0Manager.cmdIn[0]
      drv2605Face0Manager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      drv2605Face1Manager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[12]
      CdhCore.cmdDisp.compCmdSend[12] -> drv2605Face1Manager.cmdIn[0]
      drv2605Face1Manager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      drv2605Face2Manager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[13]
      CdhCore.cmdDisp.compCmdSend[13] -> drv2605Face2Manager.cmdIn[0]
      drv2605Face2Manager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      drv2605Face3Manager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[14]
      CdhCore.cmdDisp.compCmdSend[14] -> drv2605Face3Manager.cmdIn[0]
      drv2605Face3Manager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      drv2605Face5Manager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[15]
      CdhCore.cmdDisp.compCmdSend[15] -> drv2605Face5Manager.cmdIn[0]
      drv2605Face5Manager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      detumbleManager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[16]
      CdhCore.cmdDisp.compCmdSend[16] -> detumbleManager.cmdIn[0]
      detumbleManager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      face4LoadSwitch.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[17]
      CdhCore.cmdDisp.compCmdSend[17] -> face4LoadSwitch.cmdIn[0]
      face4LoadSwitch.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      face0LoadSwitch.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[18]
      CdhCore.cmdDisp.compCmdSend[18] -> face0LoadSwitch.cmdIn[0]
      face0LoadSwitch.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      face1LoadSwitch.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[19]
      CdhCore.cmdDisp.compCmdSend[19] -> face1LoadSwitch.cmdIn[0]
      face1LoadSwitch.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      face2LoadSwitch.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[20]
      CdhCore.cmdDisp.compCmdSend[20] -> face2LoadSwitch.cmdIn[0]
      face2LoadSwitch.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      face3LoadSwitch.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[21]
      CdhCore.cmdDisp.compCmdSend[21] -> face3LoadSwitch.cmdIn[0]
      face3LoadSwitch.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      face5LoadSwitch.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[22]
      CdhCore.cmdDisp.compCmdSend[22] -> face5LoadSwitch.cmdIn[0]
      face5LoadSwitch.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      payloadPowerLoadSwitch.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[23]
      CdhCore.cmdDisp.compCmdSend[23] -> payloadPowerLoadSwitch.cmdIn[0]
      payloadPowerLoadSwitch.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      payloadBatteryLoadSwitch.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[24]
      CdhCore.cmdDisp.compCmdSend[24] -> payloadBatteryLoadSwitch.cmdIn[0]
      payloadBatteryLoadSwitch.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      watchdog.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[25]
      CdhCore.cmdDisp.compCmdSend[25] -> watchdog.cmdIn[0]
      watchdog.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      rtcManager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[26]
      CdhCore.cmdDisp.compCmdSend[26] -> rtcManager.cmdIn[0]
      rtcManager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      resetManager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[27]
      CdhCore.cmdDisp.compCmdSend[27] -> resetManager.cmdIn[0]
      resetManager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      startupManager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[28]
      CdhCore.cmdDisp.compCmdSend[28] -> startupManager.cmdIn[0]
      startupManager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      powerMonitor.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[29]
      CdhCore.cmdDisp.compCmdSend[29] -> powerMonitor.cmdIn[0]
      powerMonitor.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      ina219SysManager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[30]
      CdhCore.cmdDisp.compCmdSend[30] -> ina219SysManager.cmdIn[0]
      ina219SysManager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      ina219SolManager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[31]
      CdhCore.cmdDisp.compCmdSend[31] -> ina219SolManager.cmdIn[0]
      ina219SolManager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      payloadSeq.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[32]
      CdhCore.cmdDisp.compCmdSend[32] -> payloadSeq.cmdIn[0]
      payloadSeq.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      burnwire.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[33]
      CdhCore.cmdDisp.compCmdSend[33] -> burnwire.cmdIn[0]
      burnwire.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      antennaDeployer.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[34]
      CdhCore.cmdDisp.compCmdSend[34] -> antennaDeployer.cmdIn[0]
      antennaDeployer.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      downlinkDelay.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[35]
      CdhCore.cmdDisp.compCmdSend[35] -> downlinkDelay.cmdIn[0]
      downlinkDelay.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      lora.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[36]
      CdhCore.cmdDisp.compCmdSend[36] -> lora.cmdIn[0]
      lora.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      fsFormat.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[37]
      CdhCore.cmdDisp.compCmdSend[37] -> fsFormat.cmdIn[0]
      fsFormat.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      picoTempManager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[38]
      CdhCore.cmdDisp.compCmdSend[38] -> picoTempManager.cmdIn[0]
      picoTempManager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      tmp112Face0Manager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[39]
      CdhCore.cmdDisp.compCmdSend[39] -> tmp112Face0Manager.cmdIn[0]
      tmp112Face0Manager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      tmp112Face1Manager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[40]
      CdhCore.cmdDisp.compCmdSend[40] -> tmp112Face1Manager.cmdIn[0]
      tmp112Face1Manager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      tmp112Face2Manager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[41]
      CdhCore.cmdDisp.compCmdSend[41] -> tmp112Face2Manager.cmdIn[0]
      tmp112Face2Manager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      tmp112Face3Manager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[42]
      CdhCore.cmdDisp.compCmdSend[42] -> tmp112Face3Manager.cmdIn[0]
      tmp112Face3Manager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      tmp112Face4Manager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[43]
      CdhCore.cmdDisp.compCmdSend[43] -> tmp112Face4Manager.cmdIn[0]
      tmp112Face4Manager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      tmp112Face5Manager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[44]
      CdhCore.cmdDisp.compCmdSend[44] -> tmp112Face5Manager.cmdIn[0]
      tmp112Face5Manager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      tmp112BattCell1Manager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[45]
      CdhCore.cmdDisp.compCmdSend[45] -> tmp112BattCell1Manager.cmdIn[0]
      tmp112BattCell1Manager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      tmp112BattCell2Manager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[46]
      CdhCore.cmdDisp.compCmdSend[46] -> tmp112BattCell2Manager.cmdIn[0]
      tmp112BattCell2Manager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      tmp112BattCell3Manager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[47]
      CdhCore.cmdDisp.compCmdSend[47] -> tmp112BattCell3Manager.cmdIn[0]
      tmp112BattCell3Manager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      tmp112BattCell4Manager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[48]
      CdhCore.cmdDisp.compCmdSend[48] -> tmp112BattCell4Manager.cmdIn[0]
      tmp112BattCell4Manager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      veml6031Face0Manager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[49]
      CdhCore.cmdDisp.compCmdSend[49] -> veml6031Face0Manager.cmdIn[0]
      veml6031Face0Manager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      veml6031Face1Manager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[50]
      CdhCore.cmdDisp.compCmdSend[50] -> veml6031Face1Manager.cmdIn[0]
      veml6031Face1Manager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      veml6031Face2Manager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[51]
      CdhCore.cmdDisp.compCmdSend[51] -> veml6031Face2Manager.cmdIn[0]
      veml6031Face2Manager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      veml6031Face3Manager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[52]
      CdhCore.cmdDisp.compCmdSend[52] -> veml6031Face3Manager.cmdIn[0]
      veml6031Face3Manager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      veml6031Face4Manager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[53]
      CdhCore.cmdDisp.compCmdSend[53] -> veml6031Face4Manager.cmdIn[0]
      veml6031Face4Manager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      veml6031Face5Manager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[54]
      CdhCore.cmdDisp.compCmdSend[54] -> veml6031Face5Manager.cmdIn[0]
      veml6031Face5Manager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      cameraHandler.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[55]
      CdhCore.cmdDisp.compCmdSend[55] -> cameraHandler.cmdIn[0]
      cameraHandler.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      thermalManager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[56]
      CdhCore.cmdDisp.compCmdSend[56] -> thermalManager.cmdIn[0]
      thermalManager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      ComCcsdsUart.tcSecurityDeframer.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[57]
      CdhCore.cmdDisp.compCmdSend[57] -> ComCcsdsUart.tcSecurityDeframer.cmdIn[0]
      ComCcsdsUart.tcSecurityDeframer.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
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
      rateGroup50Hz.logOut[0] -> CdhCore.events.LogRecv[0]
      rateGroup10Hz.logOut[0] -> CdhCore.events.LogRecv[0]
      rateGroup1Hz.logOut[0] -> CdhCore.events.LogRecv[0]
      chronoTime.logOut[0] -> CdhCore.events.LogRecv[0]
      cmdSeq.logOut[0] -> CdhCore.events.LogRecv[0]
      modeManager.logOut[0] -> CdhCore.events.LogRecv[0]
      imuManager.logOut[0] -> CdhCore.events.LogRecv[0]
      drv2605Face0Manager.logOut[0] -> CdhCore.events.LogRecv[0]
      drv2605Face1Manager.logOut[0] -> CdhCore.events.LogRecv[0]
      drv2605Face2Manager.logOut[0] -> CdhCore.events.LogRecv[0]
      drv2605Face3Manager.logOut[0] -> CdhCore.events.LogRecv[0]
      drv2605Face5Manager.logOut[0] -> CdhCore.events.LogRecv[0]
      detumbleManager.logOut[0] -> CdhCore.events.LogRecv[0]
      face4LoadSwitch.logOut[0] -> CdhCore.events.LogRecv[0]
      face0LoadSwitch.logOut[0] -> CdhCore.events.LogRecv[0]
      face1LoadSwitch.logOut[0] -> CdhCore.events.LogRecv[0]
      face2LoadSwitch.logOut[0] -> CdhCore.events.LogRecv[0]
      face3LoadSwitch.logOut[0] -> CdhCore.events.LogRecv[0]
      face5LoadSwitch.logOut[0] -> CdhCore.events.LogRecv[0]
      payloadPowerLoadSwitch.logOut[0] -> CdhCore.events.LogRecv[0]
      payloadBatteryLoadSwitch.logOut[0] -> CdhCore.events.LogRecv[0]
      watchdog.logOut[0] -> CdhCore.events.LogRecv[0]
      rtcManager.logOut[0] -> CdhCore.events.LogRecv[0]
      resetManager.logOut[0] -> CdhCore.events.LogRecv[0]
      startupManager.logOut[0] -> CdhCore.events.LogRecv[0]
      powerMonitor.logOut[0] -> CdhCore.events.LogRecv[0]
      ina219SysManager.logOut[0] -> CdhCore.events.LogRecv[0]
      ina219SolManager.logOut[0] -> CdhCore.events.LogRecv[0]
      payloadSeq.logOut[0] -> CdhCore.events.LogRecv[0]
      burnwire.logOut[0] -> CdhCore.events.LogRecv[0]
      antennaDeployer.logOut[0] -> CdhCore.events.LogRecv[0]
      downlinkDelay.logOut[0] -> CdhCore.events.LogRecv[0]
      lora.logOut[0] -> CdhCore.events.LogRecv[0]
      fsFormat.logOut[0] -> CdhCore.events.LogRecv[0]
      picoTempManager.logOut[0] -> CdhCore.events.LogRecv[0]
      tmp112Face0Manager.logOut[0] -> CdhCore.events.LogRecv[0]
      tmp112Face1Manager.logOut[0] -> CdhCore.events.LogRecv[0]
      tmp112Face2Manager.logOut[0] -> CdhCore.events.LogRecv[0]
      tmp112Face3Manager.logOut[0] -> CdhCore.events.LogRecv[0]
      tmp112Face4Manager.logOut[0] -> CdhCore.events.LogRecv[0]
      tmp112Face5Manager.logOut[0] -> CdhCore.events.LogRecv[0]
      tmp112BattCell1Manager.logOut[0] -> CdhCore.events.LogRecv[0]
      tmp112BattCell2Manager.logOut[0] -> CdhCore.events.LogRecv[0]
      tmp112BattCell3Manager.logOut[0] -> CdhCore.events.LogRecv[0]
      tmp112BattCell4Manager.logOut[0] -> CdhCore.events.LogRecv[0]
      veml6031Face0Manager.logOut[0] -> CdhCore.events.LogRecv[0]
      veml6031Face1Manager.logOut[0] -> CdhCore.events.LogRecv[0]
      veml6031Face2Manager.logOut[0] -> CdhCore.events.LogRecv[0]
      veml6031Face3Manager.logOut[0] -> CdhCore.events.LogRecv[0]
      veml6031Face4Manager.logOut[0] -> CdhCore.events.LogRecv[0]
      veml6031Face5Manager.logOut[0] -> CdhCore.events.LogRecv[0]
      cameraHandler.logOut[0] -> CdhCore.events.LogRecv[0]
      thermalManager.logOut[0] -> CdhCore.events.LogRecv[0]
      ComCcsdsUart.tcSecurityDeframer.logOut[0] -> CdhCore.events.LogRecv[0]
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
      rateGroup50Hz.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      rateGroup10Hz.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      rateGroup1Hz.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      chronoTime.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      cmdSeq.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      modeManager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      imuManager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      drv2605Face0Manager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      drv2605Face1Manager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      drv2605Face2Manager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      drv2605Face3Manager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      drv2605Face5Manager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      detumbleManager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      face4LoadSwitch.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      face0LoadSwitch.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      face1LoadSwitch.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      face2LoadSwitch.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      face3LoadSwitch.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      face5LoadSwitch.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      payloadPowerLoadSwitch.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      payloadBatteryLoadSwitch.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      watchdog.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      rtcManager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      resetManager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      startupManager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      powerMonitor.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ina219SysManager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ina219SolManager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      payloadSeq.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      burnwire.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      antennaDeployer.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      downlinkDelay.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      lora.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      fsFormat.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      picoTempManager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      tmp112Face0Manager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      tmp112Face1Manager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      tmp112Face2Manager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      tmp112Face3Manager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      tmp112Face4Manager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      tmp112Face5Manager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      tmp112BattCell1Manager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      tmp112BattCell2Manager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      tmp112BattCell3Manager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      tmp112BattCell4Manager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      veml6031Face0Manager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      veml6031Face1Manager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      veml6031Face2Manager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      veml6031Face3Manager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      veml6031Face4Manager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      veml6031Face5Manager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      cameraHandler.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      thermalManager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ComCcsdsUart.tcSecurityDeframer.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
    }
    connections Pattern_param {
      modeManager.prmGetOut[0] -> FileHandling.prmDb.getPrm[0]
      modeManager.prmSetOut[0] -> FileHandling.prmDb.setPrm[0]
      imuManager.prmGetOut[0] -> FileHandling.prmDb.getPrm[0]
      imuManager.prmSetOut[0] -> FileHandling.prmDb.setPrm[0]
      detumbleManager.prmGetOut[0] -> FileHandling.prmDb.getPrm[0]
      detumbleManager.prmSetOut[0] -> FileHandling.prmDb.setPrm[0]
      startupManager.prmGetOut[0] -> FileHandling.prmDb.getPrm[0]
      startupManager.prmSetOut[0] -> FileHandling.prmDb.setPrm[0]
      burnwire.prmGetOut[0] -> FileHandling.prmDb.getPrm[0]
      burnwire.prmSetOut[0] -> FileHandling.prmDb.setPrm[0]
      antennaDeployer.prmGetOut[0] -> FileHandling.prmDb.getPrm[0]
      antennaDeployer.prmSetOut[0] -> FileHandling.prmDb.setPrm[0]
      downlinkDelay.prmGetOut[0] -> FileHandling.prmDb.getPrm[0]
      downlinkDelay.prmSetOut[0] -> FileHandling.prmDb.setPrm[0]
      lora.prmGetOut[0] -> FileHandling.prmDb.getPrm[0]
      lora.prmSetOut[0] -> FileHandling.prmDb.setPrm[0]
      veml6031Face0Manager.prmGetOut[0] -> FileHandling.prmDb.getPrm[0]
      veml6031Face0Manager.prmSetOut[0] -> FileHandling.prmDb.setPrm[0]
      veml6031Face1Manager.prmGetOut[0] -> FileHandling.prmDb.getPrm[0]
      veml6031Face1Manager.prmSetOut[0] -> FileHandling.prmDb.setPrm[0]
      veml6031Face2Manager.prmGetOut[0] -> FileHandling.prmDb.getPrm[0]
      veml6031Face2Manager.prmSetOut[0] -> FileHandling.prmDb.setPrm[0]
      veml6031Face3Manager.prmGetOut[0] -> FileHandling.prmDb.getPrm[0]
      veml6031Face3Manager.prmSetOut[0] -> FileHandling.prmDb.setPrm[0]
      veml6031Face4Manager.prmGetOut[0] -> FileHandling.prmDb.getPrm[0]
      veml6031Face4Manager.prmSetOut[0] -> FileHandling.prmDb.setPrm[0]
      veml6031Face5Manager.prmGetOut[0] -> FileHandling.prmDb.getPrm[0]
      veml6031Face5Manager.prmSetOut[0] -> FileHandling.prmDb.setPrm[0]
      thermalManager.prmGetOut[0] -> FileHandling.prmDb.getPrm[0]
      thermalManager.prmSetOut[0] -> FileHandling.prmDb.setPrm[0]
      ComCcsdsUart.tcSecurityDeframer.prmGetOut[0] -> FileHandling.prmDb.getPrm[0]
      ComCcsdsUart.tcSecurityDeframer.prmSetOut[0] -> FileHandling.prmDb.setPrm[0]
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
      CdhCore.$health.PingSend[7] -> rateGroup50Hz.PingIn[0]
      rateGroup50Hz.PingOut[0] -> CdhCore.$health.PingReturn[7]
      CdhCore.$health.PingSend[8] -> rateGroup10Hz.PingIn[0]
      rateGroup10Hz.PingOut[0] -> CdhCore.$health.PingReturn[8]
      CdhCore.$health.PingSend[9] -> rateGroup1Hz.PingIn[0]
      rateGroup1Hz.PingOut[0] -> CdhCore.$health.PingReturn[9]
      CdhCore.$health.PingSend[10] -> cmdSeq.pingIn[0]
      cmdSeq.pingOut[0] -> CdhCore.$health.PingReturn[10]
      CdhCore.$health.PingSend[11] -> payloadSeq.pingIn[0]
      payloadSeq.pingOut[0] -> CdhCore.$health.PingReturn[11]
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
      rateGroup50Hz.timeCaller[0] -> chronoTime.timeGetPort[0]
      rateGroup10Hz.timeCaller[0] -> chronoTime.timeGetPort[0]
      rateGroup1Hz.timeCaller[0] -> chronoTime.timeGetPort[0]
      chronoTime.timeCaller[0] -> chronoTime.timeGetPort[0]
      cmdSeq.timeCaller[0] -> chronoTime.timeGetPort[0]
      modeManager.timeCaller[0] -> chronoTime.timeGetPort[0]
      imuManager.timeCaller[0] -> chronoTime.timeGetPort[0]
      drv2605Face0Manager.timeCaller[0] -> chronoTime.timeGetPort[0]
      drv2605Face1Manager.timeCaller[0] -> chronoTime.timeGetPort[0]
      drv2605Face2Manager.timeCaller[0] -> chronoTime.timeGetPort[0]
      drv2605Face3Manager.timeCaller[0] -> chronoTime.timeGetPort[0]
      drv2605Face5Manager.timeCaller[0] -> chronoTime.timeGetPort[0]
      detumbleManager.timeCaller[0] -> chronoTime.timeGetPort[0]
      face4LoadSwitch.timeCaller[0] -> chronoTime.timeGetPort[0]
      face0LoadSwitch.timeCaller[0] -> chronoTime.timeGetPort[0]
      face1LoadSwitch.timeCaller[0] -> chronoTime.timeGetPort[0]
      face2LoadSwitch.timeCaller[0] -> chronoTime.timeGetPort[0]
      face3LoadSwitch.timeCaller[0] -> chronoTime.timeGetPort[0]
      face5LoadSwitch.timeCaller[0] -> chronoTime.timeGetPort[0]
      payloadPowerLoadSwitch.timeCaller[0] -> chronoTime.timeGetPort[0]
      payloadBatteryLoadSwitch.timeCaller[0] -> chronoTime.timeGetPort[0]
      watchdog.timeCaller[0] -> chronoTime.timeGetPort[0]
      rtcManager.timeCaller[0] -> chronoTime.timeGetPort[0]
      resetManager.timeCaller[0] -> chronoTime.timeGetPort[0]
      startupManager.timeCaller[0] -> chronoTime.timeGetPort[0]
      powerMonitor.timeCaller[0] -> chronoTime.timeGetPort[0]
      ina219SysManager.timeCaller[0] -> chronoTime.timeGetPort[0]
      ina219SolManager.timeCaller[0] -> chronoTime.timeGetPort[0]
      payloadSeq.timeCaller[0] -> chronoTime.timeGetPort[0]
      burnwire.timeCaller[0] -> chronoTime.timeGetPort[0]
      antennaDeployer.timeCaller[0] -> chronoTime.timeGetPort[0]
      downlinkDelay.timeCaller[0] -> chronoTime.timeGetPort[0]
      lora.timeCaller[0] -> chronoTime.timeGetPort[0]
      fsFormat.timeCaller[0] -> chronoTime.timeGetPort[0]
      picoTempManager.timeCaller[0] -> chronoTime.timeGetPort[0]
      tmp112Face0Manager.timeCaller[0] -> chronoTime.timeGetPort[0]
      tmp112Face1Manager.timeCaller[0] -> chronoTime.timeGetPort[0]
      tmp112Face2Manager.timeCaller[0] -> chronoTime.timeGetPort[0]
      tmp112Face3Manager.timeCaller[0] -> chronoTime.timeGetPort[0]
      tmp112Face4Manager.timeCaller[0] -> chronoTime.timeGetPort[0]
      tmp112Face5Manager.timeCaller[0] -> chronoTime.timeGetPort[0]
      tmp112BattCell1Manager.timeCaller[0] -> chronoTime.timeGetPort[0]
      tmp112BattCell2Manager.timeCaller[0] -> chronoTime.timeGetPort[0]
      tmp112BattCell3Manager.timeCaller[0] -> chronoTime.timeGetPort[0]
      tmp112BattCell4Manager.timeCaller[0] -> chronoTime.timeGetPort[0]
      veml6031Face0Manager.timeCaller[0] -> chronoTime.timeGetPort[0]
      veml6031Face1Manager.timeCaller[0] -> chronoTime.timeGetPort[0]
      veml6031Face2Manager.timeCaller[0] -> chronoTime.timeGetPort[0]
      veml6031Face3Manager.timeCaller[0] -> chronoTime.timeGetPort[0]
      veml6031Face4Manager.timeCaller[0] -> chronoTime.timeGetPort[0]
      veml6031Face5Manager.timeCaller[0] -> chronoTime.timeGetPort[0]
      cameraHandler.timeCaller[0] -> chronoTime.timeGetPort[0]
      thermalManager.timeCaller[0] -> chronoTime.timeGetPort[0]
      ComCcsdsUart.tcSecurityDeframer.timeCaller[0] -> chronoTime.timeGetPort[0]
    }
    telemetry packets ReferenceDeploymentPackets {
      packet Beacon id 1 group 1 {
        startupManager.BootCount
        modeManager.CurrentMode
        detumbleManager.AngularVelocityMagnitude
        ina219SysManager.Voltage
        ina219SysManager.Power
        ina219SolManager.Power
        powerMonitor.TotalPowerConsumption
        powerMonitor.TotalPowerGenerated
        ComCcsdsUart.tcSecurityDeframer.CurrentSequenceNumber
        lora.BytesReceived
      }
      packet Health id 2 group 1 {
        CdhCore.cmdDisp.CommandsDispatched
        CdhCore.cmdDisp.CommandsDropped
        CdhCore.cmdDisp.CommandErrors
        rateGroup50Hz.RgMaxTime
        rateGroup10Hz.RgMaxTime
        rateGroup1Hz.RgMaxTime
        startupManager.QuiescenceEndTime
        modeManager.CurrentMode
        modeManager.SafeModeEntryCount
        modeManager.CurrentSafeModeReason
      }
      packet HealthWarnings id 3 group 1 {
        CdhCore.$health.PingLateWarnings
        rateGroup50Hz.RgCycleSlips
        rateGroup10Hz.RgCycleSlips
        rateGroup1Hz.RgCycleSlips
      }
      packet HealthAuxiliary id 4 group 5 {
        CdhCore.tlmSend.SendLevel
      }
      packet Imu id 7 group 2 {
        imuManager.AxisOrientation
        imuManager.Acceleration
        imuManager.AngularVelocity
        imuManager.MagneticField
        imuManager.AccelerometerSamplingFrequency
        imuManager.GyroscopeSamplingFrequency
        imuManager.MagnetometerSamplingFrequency
      }
      packet Radio id 8 group 2 {
        lora.LastRssi
        lora.LastSnr
        lora.BytesSent
      }
      packet LoadSwitches id 10 group 3 {
        face4LoadSwitch.IsOn
        face0LoadSwitch.IsOn
        face1LoadSwitch.IsOn
        face2LoadSwitch.IsOn
        face3LoadSwitch.IsOn
        face5LoadSwitch.IsOn
        payloadPowerLoadSwitch.IsOn
        payloadBatteryLoadSwitch.IsOn
        antennaDeployer.DeployAttemptCount
      }
      packet PowerMonitor id 11 group 2 {
        ina219SysManager.Current
        ina219SysManager.Power
        ina219SolManager.Voltage
        ina219SolManager.Current
        ina219SolManager.Power
      }
      packet Thermal id 12 group 3 {
        tmp112Face0Manager.Temperature
        tmp112Face1Manager.Temperature
        tmp112Face2Manager.Temperature
        tmp112Face3Manager.Temperature
        tmp112Face5Manager.Temperature
        tmp112BattCell1Manager.Temperature
        tmp112BattCell2Manager.Temperature
        tmp112BattCell3Manager.Temperature
        tmp112BattCell4Manager.Temperature
        picoTempManager.PicoTemperature
      }
      packet LightSensor id 13 group 2 {
        veml6031Face0Manager.VisibleLight
        veml6031Face1Manager.VisibleLight
        veml6031Face2Manager.VisibleLight
        veml6031Face3Manager.VisibleLight
        veml6031Face5Manager.VisibleLight
      }
      packet CameraDebug id 14 group 4 {
        cameraHandler.BytesReceived
        cameraHandler.ExpectedSize
        cameraHandler.IsReceiving
        cameraHandler.FileOpen
        cameraHandler.FileErrorCount
        cameraHandler.ImagesSaved
      }
      packet Detumble id 15 group 3 {
        detumbleManager.Mode
        detumbleManager.State
        detumbleManager.DetumbleStrategy
      }
      packet DetumblePerformance id 16 group 5 {
        detumbleManager.TorqueDuration
        detumbleManager.TimeBetweenMagneticFieldReadings
      }
      packet DetumbleParams id 17 group 6 {
        detumbleManager.GainParam
        detumbleManager.BdotMaxThresholdParam
        detumbleManager.DeadbandUpperThresholdParam
        detumbleManager.DeadbandLowerThresholdParam
        detumbleManager.CooldownDurationParam
        detumbleManager.TorqueDurationParam
        detumbleManager.HysteresisAxisParam
      }
      packet DetumbleXPlusCoilParams id 18 group 6 {
        detumbleManager.XPlusVoltageParam
        detumbleManager.XPlusResistanceParam
        detumbleManager.XPlusTurnsParam
        detumbleManager.XPlusLengthParam
        detumbleManager.XPlusWidthParam
        detumbleManager.XPlusShapeParam
      }
      packet DetumbleXMinusCoilParams id 19 group 6 {
        detumbleManager.XMinusVoltageParam
        detumbleManager.XMinusResistanceParam
        detumbleManager.XMinusTurnsParam
        detumbleManager.XMinusLengthParam
        detumbleManager.XMinusWidthParam
        detumbleManager.XMinusShapeParam
        detumbleManager.XTurnsParam
      }
      packet DetumbleYPlusCoilParams id 20 group 6 {
        detumbleManager.YPlusVoltageParam
        detumbleManager.YPlusResistanceParam
        detumbleManager.YPlusTurnsParam
        detumbleManager.YPlusLengthParam
        detumbleManager.YPlusWidthParam
        detumbleManager.YPlusShapeParam
      }
      packet DetumbleYMinusCoilParams id 21 group 6 {
        detumbleManager.YMinusVoltageParam
        detumbleManager.YMinusResistanceParam
        detumbleManager.YMinusTurnsParam
        detumbleManager.YMinusLengthParam
        detumbleManager.YMinusWidthParam
        detumbleManager.YMinusShapeParam
        detumbleManager.YTurnsParam
      }
      packet DetumbleZMinusCoilParams id 22 group 6 {
        detumbleManager.ZMinusVoltageParam
        detumbleManager.ZMinusResistanceParam
        detumbleManager.ZMinusTurnsParam
        detumbleManager.ZMinusDiameterParam
        detumbleManager.ZMinusShapeParam
        detumbleManager.ZTurnsParam
      }
      packet FprimeLite id 23 group 5 {
        CdhCore.cmdDisp.HandlerFaults
        CdhCore.events.EventsDropped
        CdhCore.events.HandlerFaults
        CdhCore.$health.HandlerFaults
        CdhCore.version.HandlerFaults
        CdhCore.textLogger.HandlerFaults
        CdhCore.tlmSend.HandlerFaults
        FileHandling.fileUplink.FilesReceivedFailed
        FileHandling.fileUplink.HandlerFaults
        FileHandling.fileDownlink.HandlerFaults
        FileHandling.fileManager.HandlerFaults
        FileHandling.prmDb.HandlerFaults
        rateGroupDriver.HandlerFaults
        rateGroup50Hz.RgMemberFaults
        rateGroup50Hz.HandlerFaults
        rateGroup10Hz.RgMemberFaults
        rateGroup10Hz.HandlerFaults
        rateGroup1Hz.RgMemberFaults
        rateGroup1Hz.HandlerFaults
        chronoTime.HandlerFaults
        cmdSeq.HandlerFaults
        modeManager.HandlerFaults
        imuManager.HandlerFaults
        drv2605Face0Manager.DriveLevel
        drv2605Face0Manager.HandlerFaults
        drv2605Face1Manager.DriveLevel
        drv2605Face1Manager.HandlerFaults
        drv2605Face2Manager.DriveLevel
        drv2605Face2Manager.HandlerFaults
        drv2605Face3Manager.DriveLevel
        drv2605Face3Manager.HandlerFaults
        drv2605Face5Manager.DriveLevel
        drv2605Face5Manager.HandlerFaults
        detumbleManager.IsolatedCoils
        detumbleManager.CoilStopFailures
        detumbleManager.HandlerFaults
        face4LoadSwitch.HandlerFaults
        face0LoadSwitch.HandlerFaults
        face1LoadSwitch.HandlerFaults
        face2LoadSwitch.HandlerFaults
        face3LoadSwitch.HandlerFaults
        face5LoadSwitch.HandlerFaults
        payloadPowerLoadSwitch.HandlerFaults
        payloadBatteryLoadSwitch.HandlerFaults
        watchdog.HandlerFaults
        rtcManager.HandlerFaults
        resetManager.HandlerFaults
        startupManager.HandlerFaults
        powerMonitor.HandlerFaults
        ina219SysManager.HandlerFaults
        ina219SolManager.HandlerFaults
        payloadSeq.HandlerFaults
        burnwire.HandlerFaults
        antennaDeployer.HandlerFaults
        downlinkDelay.HandlerFaults
        lora.HandlerFaults
        fsFormat.HandlerFaults
        picoTempManager.HandlerFaults
        tmp112Face0Manager.HandlerFaults
        tmp112Face1Manager.HandlerFaults
        tmp112Face2Manager.HandlerFaults
        tmp112Face3Manager.HandlerFaults
        tmp112Face4Manager.Temperature
        tmp112Face4Manager.HandlerFaults
        tmp112Face5Manager.HandlerFaults
        tmp112BattCell1Manager.HandlerFaults
        tmp112BattCell2Manager.HandlerFaults
        tmp112BattCell3Manager.HandlerFaults
        tmp112BattCell4Manager.HandlerFaults
        veml6031Face0Manager.HandlerFaults
        veml6031Face1Manager.HandlerFaults
        veml6031Face2Manager.HandlerFaults
        veml6031Face3Manager.HandlerFaults
        veml6031Face4Manager.VisibleLight
        veml6031Face4Manager.HandlerFaults
        veml6031Face5Manager.HandlerFaults
        cameraHandler.HandlerFaults
        thermalManager.HandlerFaults
        ComCcsdsUart.tcSecurityDeframer.HandlerFaults
      }
    } omit {
      CdhCore.version.FrameworkVersion
      CdhCore.version.ProjectVersion
      CdhCore.version.CustomVersion01
      CdhCore.version.CustomVersion02
      CdhCore.version.CustomVersion03
      CdhCore.version.CustomVersion04
      CdhCore.version.CustomVersion05
      CdhCore.version.CustomVersion06
      CdhCore.version.CustomVersion07
      CdhCore.version.CustomVersion08
      CdhCore.version.CustomVersion09
      CdhCore.version.CustomVersion10
      CdhCore.version.LibraryVersion01
      CdhCore.version.LibraryVersion02
      CdhCore.version.LibraryVersion03
      CdhCore.version.LibraryVersion04
      CdhCore.version.LibraryVersion05
      CdhCore.version.LibraryVersion06
      CdhCore.version.LibraryVersion07
      CdhCore.version.LibraryVersion08
      CdhCore.version.LibraryVersion09
      CdhCore.version.LibraryVersion10
      FileHandling.fileUplink.FilesReceived
      FileHandling.fileUplink.PacketsReceived
      FileHandling.fileUplink.Warnings
      FileHandling.fileDownlink.FilesSent
      FileHandling.fileDownlink.PacketsSent
      FileHandling.fileDownlink.Warnings
      FileHandling.fileManager.CommandsExecuted
      FileHandling.fileManager.Errors
      cmdSeq.CS_LoadCommands
      cmdSeq.CS_CancelCommands
      cmdSeq.CS_Errors
      cmdSeq.CS_CommandsExecuted
      cmdSeq.CS_SequencesCompleted
      watchdog.WatchdogTransitions
      payloadSeq.CS_LoadCommands
      payloadSeq.CS_CancelCommands
      payloadSeq.CS_Errors
      payloadSeq.CS_CommandsExecuted
      payloadSeq.CS_SequencesCompleted
    }
  }
}
