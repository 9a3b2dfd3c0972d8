# Written by fprime-lite (python -m fprime_lite.deploy.fpp.export deployments/adcs_ref/topology.yaml) from deployments/adcs_ref/topology.yaml.
# Regenerate it rather than edit it; tests/fprime_lite/deploy/test_fpp.py checks it is current.

module AdcsDeployment {
  topology AdcsDeployment {
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
    instance ReferenceDeployment.rateGroupDriver
    instance ReferenceDeployment.rateGroup50Hz
    instance ReferenceDeployment.rateGroup10Hz
    instance ReferenceDeployment.rateGroup1Hz
    instance ReferenceDeployment.chronoTime
    instance ReferenceDeployment.cmdSeq
    instance ReferenceDeployment.modeManager
    instance ReferenceDeployment.imuManager
    instance ReferenceDeployment.drv2605Face0Manager
    instance ReferenceDeployment.drv2605Face1Manager
    instance ReferenceDeployment.drv2605Face2Manager
    instance ReferenceDeployment.drv2605Face3Manager
    instance ReferenceDeployment.drv2605Face5Manager
    instance ReferenceDeployment.detumbleManager
    instance ReferenceDeployment.face4LoadSwitch
    instance ReferenceDeployment.face0LoadSwitch
    instance ReferenceDeployment.face1LoadSwitch
    instance ReferenceDeployment.face2LoadSwitch
    instance ReferenceDeployment.face3LoadSwitch
    instance ReferenceDeployment.face5LoadSwitch
    instance ReferenceDeployment.payloadPowerLoadSwitch
    instance ReferenceDeployment.payloadBatteryLoadSwitch
    instance ReferenceDeployment.watchdog
    instance ReferenceDeployment.rtcManager
    instance ReferenceDeployment.resetManager
    instance ReferenceDeployment.startupManager
    instance ReferenceDeployment.powerMonitor
    instance ReferenceDeployment.ina219SysManager
    instance ReferenceDeployment.ina219SolManager
    instance ReferenceDeployment.payloadSeq
    instance ReferenceDeployment.burnwire
    instance ReferenceDeployment.antennaDeployer
    instance ReferenceDeployment.downlinkDelay
    instance ReferenceDeployment.lora
    instance ReferenceDeployment.fsFormat
    instance ReferenceDeployment.picoTempManager
    instance ReferenceDeployment.tmp112Face0Manager
    instance ReferenceDeployment.tmp112Face1Manager
    instance ReferenceDeployment.tmp112Face2Manager
    instance ReferenceDeployment.tmp112Face3Manager
    instance ReferenceDeployment.tmp112Face4Manager
    instance ReferenceDeployment.tmp112Face5Manager
    instance ReferenceDeployment.tmp112BattCell1Manager
    instance ReferenceDeployment.tmp112BattCell2Manager
    instance ReferenceDeployment.tmp112BattCell3Manager
    instance ReferenceDeployment.tmp112BattCell4Manager
    instance ReferenceDeployment.veml6031Face0Manager
    instance ReferenceDeployment.veml6031Face1Manager
    instance ReferenceDeployment.veml6031Face2Manager
    instance ReferenceDeployment.veml6031Face3Manager
    instance ReferenceDeployment.veml6031Face4Manager
    instance ReferenceDeployment.veml6031Face5Manager
    instance ReferenceDeployment.cameraHandler
    instance ReferenceDeployment.thermalManager
    instance ReferenceDeployment.bdotDetumble
    instance ReferenceDeployment.attitudeController
    instance ReferenceDeployment.reactionWheel0
    instance ReferenceDeployment.reactionWheel1
    instance ReferenceDeployment.reactionWheel2
    instance ReferenceDeployment.starTracker
    instance ReferenceDeployment.orbitEphemeris
    instance ReferenceDeployment.adcs
    instance ComCcsdsUart.tcSecurityDeframer
    connections Sequencer {
      ReferenceDeployment.cmdSeq.comCmdOut[0] -> CdhCore.cmdDisp.seqCmdBuff[0]
      CdhCore.cmdDisp.seqCmdStatus[0] -> ReferenceDeployment.cmdSeq.cmdResponseIn[0]
      ReferenceDeployment.cmdSeq.seqStartOut[0] -> ReferenceDeployment.startupManager.sequenceStarted[0]
      ReferenceDeployment.cmdSeq.seqDone[0] -> ReferenceDeployment.startupManager.completeSequence[0]
      ReferenceDeployment.payloadSeq.comCmdOut[0] -> CdhCore.cmdDisp.seqCmdBuff[2]
      CdhCore.cmdDisp.seqCmdStatus[2] -> ReferenceDeployment.payloadSeq.cmdResponseIn[0]
      ReferenceDeployment.rtcManager.cancelSequences[0] -> ReferenceDeployment.cmdSeq.seqCancelIn[0]
      ReferenceDeployment.rtcManager.cancelSequences[1] -> ReferenceDeployment.payloadSeq.seqCancelIn[0]
    }
    connections Antenna {
      ReferenceDeployment.antennaDeployer.burnStart[0] -> ReferenceDeployment.burnwire.burnStart[0]
      ReferenceDeployment.antennaDeployer.burnStop[0] -> ReferenceDeployment.burnwire.burnStop[0]
    }
    connections Thermal {
      ReferenceDeployment.thermalManager.faceTempGet[0] -> ReferenceDeployment.tmp112Face0Manager.temperatureGet[0]
      ReferenceDeployment.thermalManager.faceTempGet[1] -> ReferenceDeployment.tmp112Face1Manager.temperatureGet[0]
      ReferenceDeployment.thermalManager.faceTempGet[2] -> ReferenceDeployment.tmp112Face2Manager.temperatureGet[0]
      ReferenceDeployment.thermalManager.faceTempGet[3] -> ReferenceDeployment.tmp112Face3Manager.temperatureGet[0]
      ReferenceDeployment.thermalManager.faceTempGet[4] -> ReferenceDeployment.tmp112Face5Manager.temperatureGet[0]
      ReferenceDeployment.thermalManager.battCellTempGet[0] -> ReferenceDeployment.tmp112BattCell1Manager.temperatureGet[0]
      ReferenceDeployment.thermalManager.battCellTempGet[1] -> ReferenceDeployment.tmp112BattCell2Manager.temperatureGet[0]
      ReferenceDeployment.thermalManager.battCellTempGet[2] -> ReferenceDeployment.tmp112BattCell3Manager.temperatureGet[0]
      ReferenceDeployment.thermalManager.battCellTempGet[3] -> ReferenceDeployment.tmp112BattCell4Manager.temperatureGet[0]
      ReferenceDeployment.thermalManager.picoTempGet[0] -> ReferenceDeployment.picoTempManager.picoTemperatureGet[0]
    }
    connections Radio {
      ReferenceDeployment.downlinkDelay.comStatusOut[0] -> ReferenceDeployment.lora.comStatusIn[0]
      ReferenceDeployment.lora.comStatusOut[0] -> ReferenceDeployment.downlinkDelay.comStatusIn[0]
    }
    connections Detumble {
      ReferenceDeployment.detumbleManager.angularVelocityMagnitudeGet[0] -> ReferenceDeployment.imuManager.angularVelocityMagnitudeGet[0]
      ReferenceDeployment.detumbleManager.magneticFieldGet[0] -> ReferenceDeployment.imuManager.magneticFieldGet[0]
      ReferenceDeployment.detumbleManager.magneticFieldSamplingPeriodGet[0] -> ReferenceDeployment.imuManager.magneticFieldSamplingPeriodGet[0]
      ReferenceDeployment.detumbleManager.getSystemMode[0] -> ReferenceDeployment.modeManager.getMode[0]
      ReferenceDeployment.modeManager.modeChanged[0] -> ReferenceDeployment.detumbleManager.systemModeChanged[0]
    }
    connections ModeManager {
      ReferenceDeployment.resetManager.prepareForReboot[0] -> ReferenceDeployment.modeManager.prepareForReboot[0]
      ReferenceDeployment.watchdog.prepareForReboot[0] -> ReferenceDeployment.modeManager.prepareForReboot[0]
      ReferenceDeployment.modeManager.stopWatchdog[0] -> ReferenceDeployment.watchdog.stop[0]
      ReferenceDeployment.modeManager.voltageGet[0] -> ReferenceDeployment.ina219SysManager.voltageGet[0]
      ReferenceDeployment.modeManager.loadSwitchTurnOff[0] -> ReferenceDeployment.face4LoadSwitch.turnOff[0]
      ReferenceDeployment.modeManager.loadSwitchTurnOff[1] -> ReferenceDeployment.face0LoadSwitch.turnOff[0]
      ReferenceDeployment.modeManager.loadSwitchTurnOff[2] -> ReferenceDeployment.face1LoadSwitch.turnOff[0]
      ReferenceDeployment.modeManager.loadSwitchTurnOff[3] -> ReferenceDeployment.face2LoadSwitch.turnOff[0]
      ReferenceDeployment.modeManager.loadSwitchTurnOff[4] -> ReferenceDeployment.face3LoadSwitch.turnOff[0]
      ReferenceDeployment.modeManager.loadSwitchTurnOff[5] -> ReferenceDeployment.face5LoadSwitch.turnOff[0]
      ReferenceDeployment.modeManager.loadSwitchTurnOff[6] -> ReferenceDeployment.payloadPowerLoadSwitch.turnOff[0]
      ReferenceDeployment.modeManager.loadSwitchTurnOff[7] -> ReferenceDeployment.payloadBatteryLoadSwitch.turnOff[0]
      ReferenceDeployment.modeManager.loadSwitchTurnOn[0] -> ReferenceDeployment.face4LoadSwitch.turnOn[0]
      ReferenceDeployment.modeManager.loadSwitchTurnOn[1] -> ReferenceDeployment.face0LoadSwitch.turnOn[0]
      ReferenceDeployment.modeManager.loadSwitchTurnOn[2] -> ReferenceDeployment.face1LoadSwitch.turnOn[0]
      ReferenceDeployment.modeManager.loadSwitchTurnOn[3] -> ReferenceDeployment.face2LoadSwitch.turnOn[0]
      ReferenceDeployment.modeManager.loadSwitchTurnOn[4] -> ReferenceDeployment.face3LoadSwitch.turnOn[0]
      ReferenceDeployment.modeManager.loadSwitchTurnOn[5] -> ReferenceDeployment.face5LoadSwitch.turnOn[0]
    }
    connections LoadSwitches {
      ReferenceDeployment.face0LoadSwitch.loadSwitchStateChanged[0] -> ReferenceDeployment.tmp112Face0Manager.loadSwitchStateChanged[0]
      ReferenceDeployment.face1LoadSwitch.loadSwitchStateChanged[0] -> ReferenceDeployment.tmp112Face1Manager.loadSwitchStateChanged[0]
      ReferenceDeployment.face2LoadSwitch.loadSwitchStateChanged[0] -> ReferenceDeployment.tmp112Face2Manager.loadSwitchStateChanged[0]
      ReferenceDeployment.face3LoadSwitch.loadSwitchStateChanged[0] -> ReferenceDeployment.tmp112Face3Manager.loadSwitchStateChanged[0]
      ReferenceDeployment.face4LoadSwitch.loadSwitchStateChanged[0] -> ReferenceDeployment.tmp112Face4Manager.loadSwitchStateChanged[0]
      ReferenceDeployment.face5LoadSwitch.loadSwitchStateChanged[0] -> ReferenceDeployment.tmp112Face5Manager.loadSwitchStateChanged[0]
      ReferenceDeployment.face0LoadSwitch.loadSwitchStateChanged[1] -> ReferenceDeployment.veml6031Face0Manager.loadSwitchStateChanged[0]
      ReferenceDeployment.face1LoadSwitch.loadSwitchStateChanged[1] -> ReferenceDeployment.veml6031Face1Manager.loadSwitchStateChanged[0]
      ReferenceDeployment.face2LoadSwitch.loadSwitchStateChanged[1] -> ReferenceDeployment.veml6031Face2Manager.loadSwitchStateChanged[0]
      ReferenceDeployment.face3LoadSwitch.loadSwitchStateChanged[1] -> ReferenceDeployment.veml6031Face3Manager.loadSwitchStateChanged[0]
      ReferenceDeployment.face4LoadSwitch.loadSwitchStateChanged[1] -> ReferenceDeployment.veml6031Face4Manager.loadSwitchStateChanged[0]
      ReferenceDeployment.face5LoadSwitch.loadSwitchStateChanged[1] -> ReferenceDeployment.veml6031Face5Manager.loadSwitchStateChanged[0]
      ReferenceDeployment.face0LoadSwitch.loadSwitchStateChanged[2] -> ReferenceDeployment.drv2605Face0Manager.loadSwitchStateChanged[0]
      ReferenceDeployment.face1LoadSwitch.loadSwitchStateChanged[2] -> ReferenceDeployment.drv2605Face1Manager.loadSwitchStateChanged[0]
      ReferenceDeployment.face2LoadSwitch.loadSwitchStateChanged[2] -> ReferenceDeployment.drv2605Face2Manager.loadSwitchStateChanged[0]
      ReferenceDeployment.face3LoadSwitch.loadSwitchStateChanged[2] -> ReferenceDeployment.drv2605Face3Manager.loadSwitchStateChanged[0]
      ReferenceDeployment.face5LoadSwitch.loadSwitchStateChanged[2] -> ReferenceDeployment.drv2605Face5Manager.loadSwitchStateChanged[0]
    }
    connections sysPowerMonitor {
      ReferenceDeployment.powerMonitor.sysVoltageGet[0] -> ReferenceDeployment.ina219SysManager.voltageGet[0]
      ReferenceDeployment.powerMonitor.sysCurrentGet[0] -> ReferenceDeployment.ina219SysManager.currentGet[0]
      ReferenceDeployment.powerMonitor.sysPowerGet[0] -> ReferenceDeployment.ina219SysManager.powerGet[0]
      ReferenceDeployment.powerMonitor.solVoltageGet[0] -> ReferenceDeployment.ina219SolManager.voltageGet[0]
      ReferenceDeployment.powerMonitor.solCurrentGet[0] -> ReferenceDeployment.ina219SolManager.currentGet[0]
      ReferenceDeployment.powerMonitor.solPowerGet[0] -> ReferenceDeployment.ina219SolManager.powerGet[0]
    }
    connections adcs {
      ReferenceDeployment.adcs.visibleLightGet[0] -> ReferenceDeployment.veml6031Face0Manager.visibleLightGet[0]
      ReferenceDeployment.adcs.visibleLightGet[1] -> ReferenceDeployment.veml6031Face1Manager.visibleLightGet[0]
      ReferenceDeployment.adcs.visibleLightGet[2] -> ReferenceDeployment.veml6031Face2Manager.visibleLightGet[0]
      ReferenceDeployment.adcs.visibleLightGet[3] -> ReferenceDeployment.veml6031Face3Manager.visibleLightGet[0]
      ReferenceDeployment.adcs.visibleLightGet[4] -> ReferenceDeployment.veml6031Face4Manager.visibleLightGet[0]
      ReferenceDeployment.adcs.visibleLightGet[5] -> ReferenceDeployment.veml6031Face5Manager.visibleLightGet[0]
      ReferenceDeployment.adcs.ephemerisGet[0] -> ReferenceDeployment.orbitEphemeris.ephemerisGet[0]
      ReferenceDeployment.adcs.magneticFieldGet[0] -> ReferenceDeployment.imuManager.magneticFieldGet[0]
      ReferenceDeployment.adcs.angularVelocityGet[0] -> ReferenceDeployment.imuManager.angularVelocityGet[0]
    }
    connections Attitude {
      ReferenceDeployment.attitudeController.angularVelocityGet[0] -> ReferenceDeployment.imuManager.angularVelocityGet[0]
      ReferenceDeployment.attitudeController.magneticFieldGet[0] -> ReferenceDeployment.imuManager.magneticFieldGet[0]
      ReferenceDeployment.attitudeController.attitudeGet[0] -> ReferenceDeployment.starTracker.attitudeGet[0]
      ReferenceDeployment.attitudeController.dipoleMomentGet[0] -> ReferenceDeployment.bdotDetumble.dipoleMomentGet[0]
      ReferenceDeployment.attitudeController.ephemerisGet[0] -> ReferenceDeployment.orbitEphemeris.ephemerisGet[0]
      ReferenceDeployment.attitudeController.sunVectorGet[0] -> ReferenceDeployment.adcs.sunVectorGet[0]
      ReferenceDeployment.attitudeController.getSystemMode[0] -> ReferenceDeployment.modeManager.getMode[0]
      ReferenceDeployment.bdotDetumble.magneticFieldGet[0] -> ReferenceDeployment.imuManager.magneticFieldGet[0]
      ReferenceDeployment.attitudeController.xPlusStart[0] -> ReferenceDeployment.drv2605Face0Manager.start[0]
      ReferenceDeployment.attitudeController.xPlusStop[0] -> ReferenceDeployment.drv2605Face0Manager.stop[0]
      ReferenceDeployment.attitudeController.xMinusStart[0] -> ReferenceDeployment.drv2605Face1Manager.start[0]
      ReferenceDeployment.attitudeController.xMinusStop[0] -> ReferenceDeployment.drv2605Face1Manager.stop[0]
      ReferenceDeployment.attitudeController.yPlusStart[0] -> ReferenceDeployment.drv2605Face2Manager.start[0]
      ReferenceDeployment.attitudeController.yPlusStop[0] -> ReferenceDeployment.drv2605Face2Manager.stop[0]
      ReferenceDeployment.attitudeController.yMinusStart[0] -> ReferenceDeployment.drv2605Face3Manager.start[0]
      ReferenceDeployment.attitudeController.yMinusStop[0] -> ReferenceDeployment.drv2605Face3Manager.stop[0]
      ReferenceDeployment.attitudeController.zMinusStart[0] -> ReferenceDeployment.drv2605Face5Manager.start[0]
      ReferenceDeployment.attitudeController.zMinusStop[0] -> ReferenceDeployment.drv2605Face5Manager.stop[0]
      ReferenceDeployment.attitudeController.wheelTorqueSet[0] -> ReferenceDeployment.reactionWheel0.torqueSet[0]
      ReferenceDeployment.attitudeController.wheelStateGet[0] -> ReferenceDeployment.reactionWheel0.wheelStateGet[0]
      ReferenceDeployment.attitudeController.wheelEnableSet[0] -> ReferenceDeployment.reactionWheel0.enableSet[0]
      ReferenceDeployment.attitudeController.wheelTorqueSet[1] -> ReferenceDeployment.reactionWheel1.torqueSet[0]
      ReferenceDeployment.attitudeController.wheelStateGet[1] -> ReferenceDeployment.reactionWheel1.wheelStateGet[0]
      ReferenceDeployment.attitudeController.wheelEnableSet[1] -> ReferenceDeployment.reactionWheel1.enableSet[0]
      ReferenceDeployment.attitudeController.wheelTorqueSet[2] -> ReferenceDeployment.reactionWheel2.torqueSet[0]
      ReferenceDeployment.attitudeController.wheelStateGet[2] -> ReferenceDeployment.reactionWheel2.wheelStateGet[0]
      ReferenceDeployment.attitudeController.wheelEnableSet[2] -> ReferenceDeployment.reactionWheel2.enableSet[0]
    }
    connections RateGroups {
      ReferenceDeployment.rateGroupDriver.CycleOut[0] -> ReferenceDeployment.rateGroup50Hz.CycleIn[0]
      ReferenceDeployment.rateGroup50Hz.RateGroupMemberOut[0] -> ReferenceDeployment.attitudeController.run[0]
      ReferenceDeployment.rateGroupDriver.CycleOut[1] -> ReferenceDeployment.rateGroup10Hz.CycleIn[0]
      ReferenceDeployment.rateGroup10Hz.RateGroupMemberOut[0] -> ReferenceDeployment.cmdSeq.schedIn[0]
      ReferenceDeployment.rateGroupDriver.CycleOut[2] -> ReferenceDeployment.rateGroup1Hz.CycleIn[0]
      ReferenceDeployment.rateGroup1Hz.RateGroupMemberOut[0] -> ReferenceDeployment.watchdog.run[0]
      ReferenceDeployment.rateGroup1Hz.RateGroupMemberOut[1] -> ReferenceDeployment.imuManager.run[0]
      ReferenceDeployment.rateGroup1Hz.RateGroupMemberOut[2] -> ReferenceDeployment.startupManager.run[0]
      ReferenceDeployment.rateGroup1Hz.RateGroupMemberOut[3] -> ReferenceDeployment.powerMonitor.run[0]
      ReferenceDeployment.rateGroup1Hz.RateGroupMemberOut[4] -> ReferenceDeployment.modeManager.run[0]
      ReferenceDeployment.rateGroup1Hz.RateGroupMemberOut[5] -> ReferenceDeployment.adcs.run[0]
      ReferenceDeployment.rateGroup1Hz.RateGroupMemberOut[6] -> ReferenceDeployment.reactionWheel0.run[0]
      ReferenceDeployment.rateGroup1Hz.RateGroupMemberOut[7] -> ReferenceDeployment.reactionWheel1.run[0]
      ReferenceDeployment.rateGroup1Hz.RateGroupMemberOut[8] -> ReferenceDeployment.reactionWheel2.run[0]
      ReferenceDeployment.rateGroup1Hz.RateGroupMemberOut[9] -> ReferenceDeployment.starTracker.run[0]
      ReferenceDeployment.rateGroup1Hz.RateGroupMemberOut[10] -> ReferenceDeployment.attitudeController.tlmRun[0]
      ReferenceDeployment.rateGroup1Hz.RateGroupMemberOut[11] -> CdhCore.tlmSend.Run[0]
      ReferenceDeployment.rateGroup1Hz.RateGroupMemberOut[12] -> CdhCore.$health.Run[0]
      ReferenceDeployment.rateGroup1Hz.RateGroupMemberOut[13] -> FileHandling.fileDownlink.Run[0]
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
      ReferenceDeployment.cmdSeq.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[7]
      CdhCore.cmdDisp.compCmdSend[7] -> ReferenceDeployment.cmdSeq.cmdIn[0]
      ReferenceDeployment.cmdSeq.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      ReferenceDeployment.modeManager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[8]
      CdhCore.cmdDisp.compCmdSend[8] -> ReferenceDeployment.modeManager.cmdIn[0]
      ReferenceDeployment.modeManager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      ReferenceDeployment.imuManager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[9]
      CdhCore.cmdDisp.compCmdSend[9] -> ReferenceDeployment.imuManager.cmdIn[0]
      ReferenceDeployment.imuManager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      ReferenceDeployment.drv2605Face0Manager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[10]
      CdhCore.cmdDisp.compCmdSend[10] -> ReferenceDeployment.drv2605Face0Manager.cmdIn[0]
      ReferenceDeployment.drv2605Face0Manager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      ReferenceDeployment.drv2605Face1Manager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[11]
      CdhCore.cmdDisp.compCmdSend[11] -> ReferenceDeployment.drv2605Face1Manager.cmdIn[0]
      ReferenceDeployment.drv2605Face1Manager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      ReferenceDeployment.drv2605Face2Manager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[12]
      CdhCore.cmdDisp.compCmdSend[12] -> ReferenceDeployment.drv2605Face2Manager.cmdIn[0]
      ReferenceDeployment.drv2605Face2Manager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      ReferenceDeployment.drv2605Face3Manager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[13]
      CdhCore.cmdDisp.compCmdSend[13] -> ReferenceDeployment.drv2605Face3Manager.cmdIn[0]
      ReferenceDeployment.drv2605Face3Manager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      ReferenceDeployment.drv2605Face5Manager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[14]
      CdhCore.cmdDisp.compCmdSend[14] -> ReferenceDeployment.drv2605Face5Manager.cmdIn[0]
      ReferenceDeployment.drv2605Face5Manager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      ReferenceDeployment.detumbleManager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[15]
      CdhCore.cmdDisp.compCmdSend[15] -> ReferenceDeployment.detumbleManager.cmdIn[0]
      ReferenceDeployment.detumbleManager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      ReferenceDeployment.face4LoadSwitch.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[16]
      CdhCore.cmdDisp.compCmdSend[16] -> ReferenceDeployment.face4LoadSwitch.cmdIn[0]
      ReferenceDeployment.face4LoadSwitch.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      ReferenceDeployment.face0LoadSwitch.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[17]
      CdhCore.cmdDisp.compCmdSend[17] -> ReferenceDeployment.face0LoadSwitch.cmdIn[0]
      ReferenceDeployment.face0LoadSwitch.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      ReferenceDeployment.face1LoadSwitch.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[18]
      CdhCore.cmdDisp.compCmdSend[18] -> ReferenceDeployment.face1LoadSwitch.cmdIn[0]
      ReferenceDeployment.face1LoadSwitch.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      ReferenceDeployment.face2LoadSwitch.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[19]
      CdhCore.cmdDisp.compCmdSend[19] -> ReferenceDeployment.face2LoadSwitch.cmdIn[0]
      ReferenceDeployment.face2LoadSwitch.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      ReferenceDeployment.face3LoadSwitch.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[20]
      CdhCore.cmdDisp.compCmdSend[20] -> ReferenceDeployment.face3LoadSwitch.cmdIn[0]
      ReferenceDeployment.face3LoadSwitch.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      ReferenceDeployment.face5LoadSwitch.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[21]
      CdhCore.cmdDisp.compCmdSend[21] -> ReferenceDeployment.face5LoadSwitch.cmdIn[0]
      ReferenceDeployment.face5LoadSwitch.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      ReferenceDeployment.payloadPowerLoadSwitch.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[22]
      CdhCore.cmdDisp.compCmdSend[22] -> ReferenceDeployment.payloadPowerLoadSwitch.cmdIn[0]
      ReferenceDeployment.payloadPowerLoadSwitch.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      ReferenceDeployment.payloadBatteryLoadSwitch.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[23]
      CdhCore.cmdDisp.compCmdSend[23] -> ReferenceDeployment.payloadBatteryLoadSwitch.cmdIn[0]
      ReferenceDeployment.payloadBatteryLoadSwitch.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      ReferenceDeployment.watchdog.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[24]
      CdhCore.cmdDisp.compCmdSend[24] -> ReferenceDeployment.watchdog.cmdIn[0]
      ReferenceDeployment.watchdog.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      ReferenceDeployment.rtcManager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[25]
      CdhCore.cmdDisp.compCmdSend[25] -> ReferenceDeployment.rtcManager.cmdIn[0]
      ReferenceDeployment.rtcManager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      ReferenceDeployment.resetManager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[26]
      CdhCore.cmdDisp.compCmdSend[26] -> ReferenceDeployment.resetManager.cmdIn[0]
      ReferenceDeployment.resetManager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      ReferenceDeployment.startupManager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[27]
      CdhCore.cmdDisp.compCmdSend[27] -> ReferenceDeployment.startupManager.cmdIn[0]
      ReferenceDeployment.startupManager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      ReferenceDeployment.powerMonitor.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[28]
      CdhCore.cmdDisp.compCmdSend[28] -> ReferenceDeployment.powerMonitor.cmdIn[0]
      ReferenceDeployment.powerMonitor.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      ReferenceDeployment.ina219SysManager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[29]
      CdhCore.cmdDisp.compCmdSend[29] -> ReferenceDeployment.ina219SysManager.cmdIn[0]
      ReferenceDeployment.ina219SysManager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      ReferenceDeployment.ina219SolManager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[30]
      CdhCore.cmdDisp.compCmdSend[30] -> ReferenceDeployment.ina219SolManager.cmdIn[0]
      ReferenceDeployment.ina219SolManager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      ReferenceDeployment.payloadSeq.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[31]
      CdhCore.cmdDisp.compCmdSend[31] -> ReferenceDeployment.payloadSeq.cmdIn[0]
      ReferenceDeployment.payloadSeq.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      ReferenceDeployment.burnwire.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[32]
      CdhCore.cmdDisp.compCmdSend[32] -> ReferenceDeployment.burnwire.cmdIn[0]
      ReferenceDeployment.burnwire.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      ReferenceDeployment.antennaDeployer.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[33]
      CdhCore.cmdDisp.compCmdSend[33] -> ReferenceDeployment.antennaDeployer.cmdIn[0]
      ReferenceDeployment.antennaDeployer.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      ReferenceDeployment.downlinkDelay.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[34]
      CdhCore.cmdDisp.compCmdSend[34] -> ReferenceDeployment.downlinkDelay.cmdIn[0]
      ReferenceDeployment.downlinkDelay.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      ReferenceDeployment.lora.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[35]
      CdhCore.cmdDisp.compCmdSend[35] -> ReferenceDeployment.lora.cmdIn[0]
      ReferenceDeployment.lora.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      ReferenceDeployment.fsFormat.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[36]
      CdhCore.cmdDisp.compCmdSend[36] -> ReferenceDeployment.fsFormat.cmdIn[0]
      ReferenceDeployment.fsFormat.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      ReferenceDeployment.picoTempManager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[37]
      CdhCore.cmdDisp.compCmdSend[37] -> ReferenceDeployment.picoTempManager.cmdIn[0]
      ReferenceDeployment.picoTempManager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      ReferenceDeployment.tmp112Face0Manager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[38]
      CdhCore.cmdDisp.compCmdSend[38] -> ReferenceDeployment.tmp112Face0Manager.cmdIn[0]
      ReferenceDeployment.tmp112Face0Manager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      ReferenceDeployment.tmp112Face1Manager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[39]
      CdhCore.cmdDisp.compCmdSend[39] -> ReferenceDeployment.tmp112Face1Manager.cmdIn[0]
      ReferenceDeployment.tmp112Face1Manager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      ReferenceDeployment.tmp112Face2Manager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[40]
      CdhCore.cmdDisp.compCmdSend[40] -> ReferenceDeployment.tmp112Face2Manager.cmdIn[0]
      ReferenceDeployment.tmp112Face2Manager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      ReferenceDeployment.tmp112Face3Manager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[41]
      CdhCore.cmdDisp.compCmdSend[41] -> ReferenceDeployment.tmp112Face3Manager.cmdIn[0]
      ReferenceDeployment.tmp112Face3Manager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      ReferenceDeployment.tmp112Face4Manager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[42]
      CdhCore.cmdDisp.compCmdSend[42] -> ReferenceDeployment.tmp112Face4Manager.cmdIn[0]
      ReferenceDeployment.tmp112Face4Manager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      ReferenceDeployment.tmp112Face5Manager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[43]
      CdhCore.cmdDisp.compCmdSend[43] -> ReferenceDeployment.tmp112Face5Manager.cmdIn[0]
      ReferenceDeployment.tmp112Face5Manager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      ReferenceDeployment.tmp112BattCell1Manager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[44]
      CdhCore.cmdDisp.compCmdSend[44] -> ReferenceDeployment.tmp112BattCell1Manager.cmdIn[0]
      ReferenceDeployment.tmp112BattCell1Manager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      ReferenceDeployment.tmp112BattCell2Manager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[45]
      CdhCore.cmdDisp.compCmdSend[45] -> ReferenceDeployment.tmp112BattCell2Manager.cmdIn[0]
      ReferenceDeployment.tmp112BattCell2Manager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      ReferenceDeployment.tmp112BattCell3Manager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[46]
      CdhCore.cmdDisp.compCmdSend[46] -> ReferenceDeployment.tmp112BattCell3Manager.cmdIn[0]
      ReferenceDeployment.tmp112BattCell3Manager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      ReferenceDeployment.tmp112BattCell4Manager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[47]
      CdhCore.cmdDisp.compCmdSend[47] -> ReferenceDeployment.tmp112BattCell4Manager.cmdIn[0]
      ReferenceDeployment.tmp112BattCell4Manager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      ReferenceDeployment.veml6031Face0Manager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[48]
      CdhCore.cmdDisp.compCmdSend[48] -> ReferenceDeployment.veml6031Face0Manager.cmdIn[0]
      ReferenceDeployment.veml6031Face0Manager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      ReferenceDeployment.veml6031Face1Manager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[49]
      CdhCore.cmdDisp.compCmdSend[49] -> ReferenceDeployment.veml6031Face1Manager.cmdIn[0]
      ReferenceDeployment.veml6031Face1Manager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      ReferenceDeployment.veml6031Face2Manager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[50]
      CdhCore.cmdDisp.compCmdSend[50] -> ReferenceDeployment.veml6031Face2Manager.cmdIn[0]
      ReferenceDeployment.veml6031Face2Manager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      ReferenceDeployment.veml6031Face3Manager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[51]
      CdhCore.cmdDisp.compCmdSend[51] -> ReferenceDeployment.veml6031Face3Manager.cmdIn[0]
      ReferenceDeployment.veml6031Face3Manager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      ReferenceDeployment.veml6031Face4Manager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[52]
      CdhCore.cmdDisp.compCmdSend[52] -> ReferenceDeployment.veml6031Face4Manager.cmdIn[0]
      ReferenceDeployment.veml6031Face4Manager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      ReferenceDeployment.veml6031Face5Manager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[53]
      CdhCore.cmdDisp.compCmdSend[53] -> ReferenceDeployment.veml6031Face5Manager.cmdIn[0]
      ReferenceDeployment.veml6031Face5Manager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      ReferenceDeployment.cameraHandler.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[54]
      CdhCore.cmdDisp.compCmdSend[54] -> ReferenceDeployment.cameraHandler.cmdIn[0]
      ReferenceDeployment.cameraHandler.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      ReferenceDeployment.thermalManager.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[55]
      CdhCore.cmdDisp.compCmdSend[55] -> ReferenceDeployment.thermalManager.cmdIn[0]
      ReferenceDeployment.thermalManager.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      ReferenceDeployment.bdotDetumble.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[56]
      CdhCore.cmdDisp.compCmdSend[56] -> ReferenceDeployment.bdotDetumble.cmdIn[0]
      ReferenceDeployment.bdotDetumble.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      ReferenceDeployment.attitudeController.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[57]
      CdhCore.cmdDisp.compCmdSend[57] -> ReferenceDeployment.attitudeController.cmdIn[0]
      ReferenceDeployment.attitudeController.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      ReferenceDeployment.reactionWheel0.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[58]
      CdhCore.cmdDisp.compCmdSend[58] -> ReferenceDeployment.reactionWheel0.cmdIn[0]
      ReferenceDeployment.reactionWheel0.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      ReferenceDeployment.reactionWheel1.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[59]
      CdhCore.cmdDisp.compCmdSend[59] -> ReferenceDeployment.reactionWheel1.cmdIn[0]
      ReferenceDeployment.reactionWheel1.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      ReferenceDeployment.reactionWheel2.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[60]
      CdhCore.cmdDisp.compCmdSend[60] -> ReferenceDeployment.reactionWheel2.cmdIn[0]
      ReferenceDeployment.reactionWheel2.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      ReferenceDeployment.starTracker.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[61]
      CdhCore.cmdDisp.compCmdSend[61] -> ReferenceDeployment.starTracker.cmdIn[0]
      ReferenceDeployment.starTracker.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      ReferenceDeployment.adcs.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[62]
      CdhCore.cmdDisp.compCmdSend[62] -> ReferenceDeployment.adcs.cmdIn[0]
      ReferenceDeployment.adcs.cmdResponseOut[0] -> CdhCore.cmdDisp.compCmdStat[0]
      ComCcsdsUart.tcSecurityDeframer.cmdRegOut[0] -> CdhCore.cmdDisp.compCmdReg[63]
      CdhCore.cmdDisp.compCmdSend[63] -> ComCcsdsUart.tcSecurityDeframer.cmdIn[0]
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
      ReferenceDeployment.rateGroupDriver.logOut[0] -> CdhCore.events.LogRecv[0]
      ReferenceDeployment.rateGroup50Hz.logOut[0] -> CdhCore.events.LogRecv[0]
      ReferenceDeployment.rateGroup10Hz.logOut[0] -> CdhCore.events.LogRecv[0]
      ReferenceDeployment.rateGroup1Hz.logOut[0] -> CdhCore.events.LogRecv[0]
      ReferenceDeployment.chronoTime.logOut[0] -> CdhCore.events.LogRecv[0]
      ReferenceDeployment.cmdSeq.logOut[0] -> CdhCore.events.LogRecv[0]
      ReferenceDeployment.modeManager.logOut[0] -> CdhCore.events.LogRecv[0]
      ReferenceDeployment.imuManager.logOut[0] -> CdhCore.events.LogRecv[0]
      ReferenceDeployment.drv2605Face0Manager.logOut[0] -> CdhCore.events.LogRecv[0]
      ReferenceDeployment.drv2605Face1Manager.logOut[0] -> CdhCore.events.LogRecv[0]
      ReferenceDeployment.drv2605Face2Manager.logOut[0] -> CdhCore.events.LogRecv[0]
      ReferenceDeployment.drv2605Face3Manager.logOut[0] -> CdhCore.events.LogRecv[0]
      ReferenceDeployment.drv2605Face5Manager.logOut[0] -> CdhCore.events.LogRecv[0]
      ReferenceDeployment.detumbleManager.logOut[0] -> CdhCore.events.LogRecv[0]
      ReferenceDeployment.face4LoadSwitch.logOut[0] -> CdhCore.events.LogRecv[0]
      ReferenceDeployment.face0LoadSwitch.logOut[0] -> CdhCore.events.LogRecv[0]
      ReferenceDeployment.face1LoadSwitch.logOut[0] -> CdhCore.events.LogRecv[0]
      ReferenceDeployment.face2LoadSwitch.logOut[0] -> CdhCore.events.LogRecv[0]
      ReferenceDeployment.face3LoadSwitch.logOut[0] -> CdhCore.events.LogRecv[0]
      ReferenceDeployment.face5LoadSwitch.logOut[0] -> CdhCore.events.LogRecv[0]
      ReferenceDeployment.payloadPowerLoadSwitch.logOut[0] -> CdhCore.events.LogRecv[0]
      ReferenceDeployment.payloadBatteryLoadSwitch.logOut[0] -> CdhCore.events.LogRecv[0]
      ReferenceDeployment.watchdog.logOut[0] -> CdhCore.events.LogRecv[0]
      ReferenceDeployment.rtcManager.logOut[0] -> CdhCore.events.LogRecv[0]
      ReferenceDeployment.resetManager.logOut[0] -> CdhCore.events.LogRecv[0]
      ReferenceDeployment.startupManager.logOut[0] -> CdhCore.events.LogRecv[0]
      ReferenceDeployment.powerMonitor.logOut[0] -> CdhCore.events.LogRecv[0]
      ReferenceDeployment.ina219SysManager.logOut[0] -> CdhCore.events.LogRecv[0]
      ReferenceDeployment.ina219SolManager.logOut[0] -> CdhCore.events.LogRecv[0]
      ReferenceDeployment.payloadSeq.logOut[0] -> CdhCore.events.LogRecv[0]
      ReferenceDeployment.burnwire.logOut[0] -> CdhCore.events.LogRecv[0]
      ReferenceDeployment.antennaDeployer.logOut[0] -> CdhCore.events.LogRecv[0]
      ReferenceDeployment.downlinkDelay.logOut[0] -> CdhCore.events.LogRecv[0]
      ReferenceDeployment.lora.logOut[0] -> CdhCore.events.LogRecv[0]
      ReferenceDeployment.fsFormat.logOut[0] -> CdhCore.events.LogRecv[0]
      ReferenceDeployment.picoTempManager.logOut[0] -> CdhCore.events.LogRecv[0]
      ReferenceDeployment.tmp112Face0Manager.logOut[0] -> CdhCore.events.LogRecv[0]
      ReferenceDeployment.tmp112Face1Manager.logOut[0] -> CdhCore.events.LogRecv[0]
      ReferenceDeployment.tmp112Face2Manager.logOut[0] -> CdhCore.events.LogRecv[0]
      ReferenceDeployment.tmp112Face3Manager.logOut[0] -> CdhCore.events.LogRecv[0]
      ReferenceDeployment.tmp112Face4Manager.logOut[0] -> CdhCore.events.LogRecv[0]
      ReferenceDeployment.tmp112Face5Manager.logOut[0] -> CdhCore.events.LogRecv[0]
      ReferenceDeployment.tmp112BattCell1Manager.logOut[0] -> CdhCore.events.LogRecv[0]
      ReferenceDeployment.tmp112BattCell2Manager.logOut[0] -> CdhCore.events.LogRecv[0]
      ReferenceDeployment.tmp112BattCell3Manager.logOut[0] -> CdhCore.events.LogRecv[0]
      ReferenceDeployment.tmp112BattCell4Manager.logOut[0] -> CdhCore.events.LogRecv[0]
      ReferenceDeployment.veml6031Face0Manager.logOut[0] -> CdhCore.events.LogRecv[0]
      ReferenceDeployment.veml6031Face1Manager.logOut[0] -> CdhCore.events.LogRecv[0]
      ReferenceDeployment.veml6031Face2Manager.logOut[0] -> CdhCore.events.LogRecv[0]
      ReferenceDeployment.veml6031Face3Manager.logOut[0] -> CdhCore.events.LogRecv[0]
      ReferenceDeployment.veml6031Face4Manager.logOut[0] -> CdhCore.events.LogRecv[0]
      ReferenceDeployment.veml6031Face5Manager.logOut[0] -> CdhCore.events.LogRecv[0]
      ReferenceDeployment.cameraHandler.logOut[0] -> CdhCore.events.LogRecv[0]
      ReferenceDeployment.thermalManager.logOut[0] -> CdhCore.events.LogRecv[0]
      ReferenceDeployment.bdotDetumble.logOut[0] -> CdhCore.events.LogRecv[0]
      ReferenceDeployment.attitudeController.logOut[0] -> CdhCore.events.LogRecv[0]
      ReferenceDeployment.reactionWheel0.logOut[0] -> CdhCore.events.LogRecv[0]
      ReferenceDeployment.reactionWheel1.logOut[0] -> CdhCore.events.LogRecv[0]
      ReferenceDeployment.reactionWheel2.logOut[0] -> CdhCore.events.LogRecv[0]
      ReferenceDeployment.starTracker.logOut[0] -> CdhCore.events.LogRecv[0]
      ReferenceDeployment.orbitEphemeris.logOut[0] -> CdhCore.events.LogRecv[0]
      ReferenceDeployment.adcs.logOut[0] -> CdhCore.events.LogRecv[0]
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
      ReferenceDeployment.rateGroupDriver.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ReferenceDeployment.rateGroup50Hz.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ReferenceDeployment.rateGroup10Hz.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ReferenceDeployment.rateGroup1Hz.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ReferenceDeployment.chronoTime.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ReferenceDeployment.cmdSeq.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ReferenceDeployment.modeManager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ReferenceDeployment.imuManager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ReferenceDeployment.drv2605Face0Manager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ReferenceDeployment.drv2605Face1Manager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ReferenceDeployment.drv2605Face2Manager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ReferenceDeployment.drv2605Face3Manager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ReferenceDeployment.drv2605Face5Manager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ReferenceDeployment.detumbleManager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ReferenceDeployment.face4LoadSwitch.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ReferenceDeployment.face0LoadSwitch.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ReferenceDeployment.face1LoadSwitch.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ReferenceDeployment.face2LoadSwitch.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ReferenceDeployment.face3LoadSwitch.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ReferenceDeployment.face5LoadSwitch.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ReferenceDeployment.payloadPowerLoadSwitch.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ReferenceDeployment.payloadBatteryLoadSwitch.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ReferenceDeployment.watchdog.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ReferenceDeployment.rtcManager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ReferenceDeployment.resetManager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ReferenceDeployment.startupManager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ReferenceDeployment.powerMonitor.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ReferenceDeployment.ina219SysManager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ReferenceDeployment.ina219SolManager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ReferenceDeployment.payloadSeq.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ReferenceDeployment.burnwire.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ReferenceDeployment.antennaDeployer.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ReferenceDeployment.downlinkDelay.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ReferenceDeployment.lora.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ReferenceDeployment.fsFormat.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ReferenceDeployment.picoTempManager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ReferenceDeployment.tmp112Face0Manager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ReferenceDeployment.tmp112Face1Manager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ReferenceDeployment.tmp112Face2Manager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ReferenceDeployment.tmp112Face3Manager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ReferenceDeployment.tmp112Face4Manager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ReferenceDeployment.tmp112Face5Manager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ReferenceDeployment.tmp112BattCell1Manager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ReferenceDeployment.tmp112BattCell2Manager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ReferenceDeployment.tmp112BattCell3Manager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ReferenceDeployment.tmp112BattCell4Manager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ReferenceDeployment.veml6031Face0Manager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ReferenceDeployment.veml6031Face1Manager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ReferenceDeployment.veml6031Face2Manager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ReferenceDeployment.veml6031Face3Manager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ReferenceDeployment.veml6031Face4Manager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ReferenceDeployment.veml6031Face5Manager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ReferenceDeployment.cameraHandler.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ReferenceDeployment.thermalManager.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ReferenceDeployment.bdotDetumble.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ReferenceDeployment.attitudeController.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ReferenceDeployment.reactionWheel0.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ReferenceDeployment.reactionWheel1.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ReferenceDeployment.reactionWheel2.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ReferenceDeployment.starTracker.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ReferenceDeployment.orbitEphemeris.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ReferenceDeployment.adcs.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
      ComCcsdsUart.tcSecurityDeframer.tlmOut[0] -> CdhCore.tlmSend.TlmRecv[0]
    }
    connections Pattern_param {
      ReferenceDeployment.modeManager.prmGetOut[0] -> FileHandling.prmDb.getPrm[0]
      ReferenceDeployment.modeManager.prmSetOut[0] -> FileHandling.prmDb.setPrm[0]
      ReferenceDeployment.imuManager.prmGetOut[0] -> FileHandling.prmDb.getPrm[0]
      ReferenceDeployment.imuManager.prmSetOut[0] -> FileHandling.prmDb.setPrm[0]
      ReferenceDeployment.detumbleManager.prmGetOut[0] -> FileHandling.prmDb.getPrm[0]
      ReferenceDeployment.detumbleManager.prmSetOut[0] -> FileHandling.prmDb.setPrm[0]
      ReferenceDeployment.startupManager.prmGetOut[0] -> FileHandling.prmDb.getPrm[0]
      ReferenceDeployment.startupManager.prmSetOut[0] -> FileHandling.prmDb.setPrm[0]
      ReferenceDeployment.burnwire.prmGetOut[0] -> FileHandling.prmDb.getPrm[0]
      ReferenceDeployment.burnwire.prmSetOut[0] -> FileHandling.prmDb.setPrm[0]
      ReferenceDeployment.antennaDeployer.prmGetOut[0] -> FileHandling.prmDb.getPrm[0]
      ReferenceDeployment.antennaDeployer.prmSetOut[0] -> FileHandling.prmDb.setPrm[0]
      ReferenceDeployment.downlinkDelay.prmGetOut[0] -> FileHandling.prmDb.getPrm[0]
      ReferenceDeployment.downlinkDelay.prmSetOut[0] -> FileHandling.prmDb.setPrm[0]
      ReferenceDeployment.lora.prmGetOut[0] -> FileHandling.prmDb.getPrm[0]
      ReferenceDeployment.lora.prmSetOut[0] -> FileHandling.prmDb.setPrm[0]
      ReferenceDeployment.veml6031Face0Manager.prmGetOut[0] -> FileHandling.prmDb.getPrm[0]
      ReferenceDeployment.veml6031Face0Manager.prmSetOut[0] -> FileHandling.prmDb.setPrm[0]
      ReferenceDeployment.veml6031Face1Manager.prmGetOut[0] -> FileHandling.prmDb.getPrm[0]
      ReferenceDeployment.veml6031Face1Manager.prmSetOut[0] -> FileHandling.prmDb.setPrm[0]
      ReferenceDeployment.veml6031Face2Manager.prmGetOut[0] -> FileHandling.prmDb.getPrm[0]
      ReferenceDeployment.veml6031Face2Manager.prmSetOut[0] -> FileHandling.prmDb.setPrm[0]
      ReferenceDeployment.veml6031Face3Manager.prmGetOut[0] -> FileHandling.prmDb.getPrm[0]
      ReferenceDeployment.veml6031Face3Manager.prmSetOut[0] -> FileHandling.prmDb.setPrm[0]
      ReferenceDeployment.veml6031Face4Manager.prmGetOut[0] -> FileHandling.prmDb.getPrm[0]
      ReferenceDeployment.veml6031Face4Manager.prmSetOut[0] -> FileHandling.prmDb.setPrm[0]
      ReferenceDeployment.veml6031Face5Manager.prmGetOut[0] -> FileHandling.prmDb.getPrm[0]
      ReferenceDeployment.veml6031Face5Manager.prmSetOut[0] -> FileHandling.prmDb.setPrm[0]
      ReferenceDeployment.thermalManager.prmGetOut[0] -> FileHandling.prmDb.getPrm[0]
      ReferenceDeployment.thermalManager.prmSetOut[0] -> FileHandling.prmDb.setPrm[0]
      ReferenceDeployment.bdotDetumble.prmGetOut[0] -> FileHandling.prmDb.getPrm[0]
      ReferenceDeployment.bdotDetumble.prmSetOut[0] -> FileHandling.prmDb.setPrm[0]
      ReferenceDeployment.attitudeController.prmGetOut[0] -> FileHandling.prmDb.getPrm[0]
      ReferenceDeployment.attitudeController.prmSetOut[0] -> FileHandling.prmDb.setPrm[0]
      ReferenceDeployment.adcs.prmGetOut[0] -> FileHandling.prmDb.getPrm[0]
      ReferenceDeployment.adcs.prmSetOut[0] -> FileHandling.prmDb.setPrm[0]
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
      CdhCore.$health.PingSend[7] -> ReferenceDeployment.rateGroup50Hz.PingIn[0]
      ReferenceDeployment.rateGroup50Hz.PingOut[0] -> CdhCore.$health.PingReturn[7]
      CdhCore.$health.PingSend[8] -> ReferenceDeployment.rateGroup10Hz.PingIn[0]
      ReferenceDeployment.rateGroup10Hz.PingOut[0] -> CdhCore.$health.PingReturn[8]
      CdhCore.$health.PingSend[9] -> ReferenceDeployment.rateGroup1Hz.PingIn[0]
      ReferenceDeployment.rateGroup1Hz.PingOut[0] -> CdhCore.$health.PingReturn[9]
      CdhCore.$health.PingSend[10] -> ReferenceDeployment.cmdSeq.pingIn[0]
      ReferenceDeployment.cmdSeq.pingOut[0] -> CdhCore.$health.PingReturn[10]
      CdhCore.$health.PingSend[11] -> ReferenceDeployment.payloadSeq.pingIn[0]
      ReferenceDeployment.payloadSeq.pingOut[0] -> CdhCore.$health.PingReturn[11]
    }
    connections Pattern_time {
      CdhCore.cmdDisp.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      CdhCore.events.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      CdhCore.$health.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      CdhCore.version.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      CdhCore.textLogger.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      CdhCore.tlmSend.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      FileHandling.fileUplink.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      FileHandling.fileDownlink.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      FileHandling.fileManager.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      FileHandling.prmDb.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      ReferenceDeployment.rateGroupDriver.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      ReferenceDeployment.rateGroup50Hz.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      ReferenceDeployment.rateGroup10Hz.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      ReferenceDeployment.rateGroup1Hz.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      ReferenceDeployment.chronoTime.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      ReferenceDeployment.cmdSeq.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      ReferenceDeployment.modeManager.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      ReferenceDeployment.imuManager.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      ReferenceDeployment.drv2605Face0Manager.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      ReferenceDeployment.drv2605Face1Manager.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      ReferenceDeployment.drv2605Face2Manager.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      ReferenceDeployment.drv2605Face3Manager.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      ReferenceDeployment.drv2605Face5Manager.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      ReferenceDeployment.detumbleManager.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      ReferenceDeployment.face4LoadSwitch.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      ReferenceDeployment.face0LoadSwitch.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      ReferenceDeployment.face1LoadSwitch.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      ReferenceDeployment.face2LoadSwitch.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      ReferenceDeployment.face3LoadSwitch.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      ReferenceDeployment.face5LoadSwitch.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      ReferenceDeployment.payloadPowerLoadSwitch.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      ReferenceDeployment.payloadBatteryLoadSwitch.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      ReferenceDeployment.watchdog.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      ReferenceDeployment.rtcManager.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      ReferenceDeployment.resetManager.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      ReferenceDeployment.startupManager.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      ReferenceDeployment.powerMonitor.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      ReferenceDeployment.ina219SysManager.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      ReferenceDeployment.ina219SolManager.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      ReferenceDeployment.payloadSeq.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      ReferenceDeployment.burnwire.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      ReferenceDeployment.antennaDeployer.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      ReferenceDeployment.downlinkDelay.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      ReferenceDeployment.lora.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      ReferenceDeployment.fsFormat.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      ReferenceDeployment.picoTempManager.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      ReferenceDeployment.tmp112Face0Manager.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      ReferenceDeployment.tmp112Face1Manager.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      ReferenceDeployment.tmp112Face2Manager.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      ReferenceDeployment.tmp112Face3Manager.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      ReferenceDeployment.tmp112Face4Manager.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      ReferenceDeployment.tmp112Face5Manager.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      ReferenceDeployment.tmp112BattCell1Manager.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      ReferenceDeployment.tmp112BattCell2Manager.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      ReferenceDeployment.tmp112BattCell3Manager.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      ReferenceDeployment.tmp112BattCell4Manager.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      ReferenceDeployment.veml6031Face0Manager.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      ReferenceDeployment.veml6031Face1Manager.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      ReferenceDeployment.veml6031Face2Manager.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      ReferenceDeployment.veml6031Face3Manager.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      ReferenceDeployment.veml6031Face4Manager.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      ReferenceDeployment.veml6031Face5Manager.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      ReferenceDeployment.cameraHandler.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      ReferenceDeployment.thermalManager.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      ReferenceDeployment.bdotDetumble.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      ReferenceDeployment.attitudeController.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      ReferenceDeployment.reactionWheel0.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      ReferenceDeployment.reactionWheel1.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      ReferenceDeployment.reactionWheel2.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      ReferenceDeployment.starTracker.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      ReferenceDeployment.orbitEphemeris.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      ReferenceDeployment.adcs.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
      ComCcsdsUart.tcSecurityDeframer.timeCaller[0] -> ReferenceDeployment.chronoTime.timeGetPort[0]
    }
  }
}

module CdhCore {
  instance cmdDisp: Svc.CommandDispatcher base id 0x01000100 queue size 10

  instance events: Svc.EventManager base id 0x01000200 queue size 10

  instance $health: Svc.Health base id 0x01000300 queue size 25

  instance version: Svc.Version base id 0x01000400

  instance textLogger: Svc.PassiveTextLogger base id 0x01000500

  instance tlmSend: Svc.TlmChan base id 0x01006000 queue size 10
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

  instance bdotDetumble: Components.BDotDetumble base id 0x1005B000

  instance attitudeController: Components.AttitudeController base id 0x1005C000

  instance reactionWheel0: Components.ReactionWheelDriver base id 0x1005D000

  instance reactionWheel1: Components.ReactionWheelDriver base id 0x1005E000

  instance reactionWheel2: Components.ReactionWheelDriver base id 0x1005F000

  instance starTracker: Components.StarTracker base id 0x10061000

  instance orbitEphemeris: Components.OrbitEphemeris base id 0x10063000

  instance adcs: Components.ADCS base id 0x1004C000
}
