module Demo {

  instance rateGroupDriver: Svc.RateGroupDriver base id 0x1000
  instance rateGroup1Hz: Svc.ActiveRateGroup base id 0x2000 queue size 10
  instance lampSwitch: Components.LampSwitch base id 0x100 queue size 4

  @ The lamp switch on a 1 Hz rate group: each tick sends its state machine a toggle
  topology Demo {
    instance rateGroupDriver
    instance rateGroup1Hz
    instance lampSwitch
    connections RateGroups {
      rateGroupDriver.CycleOut[0] -> rateGroup1Hz.CycleIn[0]
      rateGroup1Hz.RateGroupMemberOut[0] -> lampSwitch.run[0]
    }
  }

}
