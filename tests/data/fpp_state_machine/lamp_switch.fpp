module Components {

  @ A lamp: OFF, or ON and then DIM or BRIGHT; a level signal chooses between them
  state machine Lamp {
    signal toggle
    @ the requested level, 0-255
    signal level: U8
    signal reset
    action countEntry
    action setLevel: U8
    action log
    guard bright: U8
    guard allowed
    initial do { log } enter OFF
    state OFF {
      entry do { countEntry }
      exit do { log }
      on toggle if allowed enter ON
      on reset enter ON.BRIGHT
    }
    state ON {
      initial enter DIM
      entry do { countEntry }
      exit do { log }
      on toggle enter OFF
      on level enter CHECK
      on reset do { log } enter OFF
      choice CHECK { if bright do { setLevel } enter BRIGHT else do { setLevel } enter DIM }
      state DIM {
        entry do { countEntry }
      }
      state BRIGHT {
        entry do { countEntry }
        on reset enter BRIGHT
        on toggle do { log }
      }
    }
  }

  @ Switches a lamp; the rate group's tick asks for a toggle
  queued component LampSwitch {
    state machine instance lamp: Lamp priority 3 drop
    async input port run: Svc.Sched
    time get port timeCaller
  }

}

module Demo {
  instance lampSwitch: Components.LampSwitch base id 0x100 queue size 4
  topology Demo {
    instance lampSwitch
  }
}
