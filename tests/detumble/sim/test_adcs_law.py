"""The plant-only three-mode controller (detumble.sim.adcs_law, an adapter of detumble.control.three_mode): one
law and one source of defaults shared with the flight component, no framework import, the deployment's timing, and
scenario/CLI plumbing (issues 13, 19 and 26)."""

import json
import math
import subprocess
import sys

import pytest

from detumble.control import attitude_defaults
from detumble.sim.adcs_law import COIL_FACES, AdcsLaw, PlantIo, pointing_statistics
from detumble.sim.plant import Plant
from detumble.sim.runner import LawError, main, make_law, run
from detumble.sim.scenario import ScenarioError, load_scenario


def test_component_parameter_defaults_are_the_shared_module_s():
    """ADCS-070: every AttitudeController parameter takes its default from detumble.control.attitude_defaults
    (same names, same values; enums by member name), so the plant-only law starts where the component does."""
    from detumble.components.attitude_controller import BORESIGHT_B, AttitudeController

    params = AttitudeController("c").params
    assert set(params) == set(attitude_defaults.DEFAULTS)
    for name, bound in params.items():
        value = bound.value
        assert (value.name if hasattr(value, "name") else value) == attitude_defaults.DEFAULTS[name], name
    assert BORESIGHT_B == attitude_defaults.BORESIGHT_B
    from detumble.components.bdot_detumble import BDotDetumble

    assert BDotDetumble("b").params["Gain"].value == attitude_defaults.BDOT_PROVIDER_GAIN
    for name, choices in attitude_defaults.ENUM_CHOICES.items():
        enum = type(params[name].value)
        assert tuple(m.name for m in enum) == choices, name
        assert [int(m) for m in enum] == list(range(len(choices))), name  # the law takes them by index
    from detumble.components.attitude_types import ControlAutonomy, ControlMode, ModeChangeReason
    from detumble.control import three_mode

    assert [(m.name, int(m)) for m in ControlMode] == [(n, i) for i, n in enumerate(three_mode.MODES)]
    assert [(m.name, int(m)) for m in ModeChangeReason] == [(n, i) for i, n in enumerate(three_mode.REASONS)]
    assert (int(ControlAutonomy.MANUAL), int(ControlAutonomy.AUTO)) == (three_mode.MANUAL, three_mode.AUTO)
    declared = AttitudeController.__fprime_spec__.params
    assert [p.name for p in declared] == list(attitude_defaults.PARAMETERS)
    for p in declared:  # the declared ranges are the table's
        _units, low, high, finite = attitude_defaults.PARAMETERS[p.name]
        assert (p.low, p.high, p.finite) == (low, high, finite), p.name


def test_law_and_defaults_import_no_framework():
    """ADCS-071: the law, its plant-only adapter, the runner and the defaults import nothing of fprime_lite."""
    code = ("import sys, detumble.control.three_mode, detumble.sim.adcs_law, detumble.sim.runner, "
            "detumble.control.attitude_defaults; "
            "print([m for m in sys.modules if m.split('.')[0] == 'fprime_lite'])")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "[]"


def test_coil_maxima_defaults_match_the_adcs_plant():
    """The component's coil defaults (per coil) are what the adcs scenario's coils give at full drive."""
    plant = Plant(load_scenario("adcs"))
    d = attitude_defaults
    assert plant.max_dipole_per_axis() == pytest.approx(
        (2 * d.X_COIL_MAX_DIPOLE, 2 * d.Y_COIL_MAX_DIPOLE, d.Z_COIL_MAX_DIPOLE), rel=1e-12)


class _Io(PlantIo):
    """A PlantIo that logs what the law does to the plant, tick by tick."""

    def __init__(self, plant):
        super().__init__(plant)
        self.log = []

    def gyro(self):
        self.log.append(("gyro", self.now_us()))
        return super().gyro()

    def drive_coils(self, levels, dipole_B):
        self.log.append(("coils", self.now_us(), tuple(levels)))
        super().drive_coils(levels, dipole_B)


def test_timing_is_the_component_s_tick_cycle_and_cooldown():
    """ADCS-072: one tick per 20 ms, a control cycle every CYCLE_TICKS = 5 ticks (10 Hz) with the gyro averaged
    over the cycle's five readings, the coils off on the last tick of each cycle; AUTO from auto_start_s."""
    plant = Plant(load_scenario("adcs"))
    law = make_law("adcs", plant)
    io = _Io(plant)
    assert law.tick_s == 0.02 and law.cycle_ticks == 5
    for _ in range(30):
        law.tick(io)
        plant.step(0.02)
    assert law.cycles == 6 and law.ticks == 30
    assert sum(1 for e in io.log if e[0] == "gyro") == 30
    # scenario adcs: AUTO from 0.1 s (the deployment's SET_AUTO); IDLE at the first cycle, then DETUMBLE
    assert law.transitions[0] == (0.1, "DETUMBLE", "AUTO_START")
    drives = [e for e in io.log if e[0] == "coils"]
    on = [e[1] for e in drives if any(e[2])]
    off = [e[1] for e in drives if not any(e[2])]
    assert on and all(t % 100_000 == 0 for t in on)  # driven on cycle ticks
    assert off and all(t % 100_000 == 80_000 for t in off)  # off on the last tick of each cycle
    assert on[0] == 200_000  # B-dot primes at 0.1 s, first dipole at 0.2 s
    assert COIL_FACES == (0, 1, 2, 3, 5)


def test_parameters_and_target_come_from_control_adcs():
    sc = load_scenario("adcs", settings=["control.adcs.K_P=2.0e-3", "control.adcs.SPIN_LAW=VIRTUAL_DAMPER",
                                         "control.adcs.target_q_bn=[1, 0, 0, 0]"])
    law = make_law("adcs", Plant(sc))
    assert law.params["K_P"] == 2.0e-3 and law.params["SPIN_LAW"] == "VIRTUAL_DAMPER"
    assert law.params["K_D"] == attitude_defaults.K_D
    assert law.target == (1.0, 0.0, 0.0, 0.0)
    with pytest.raises(ScenarioError, match="control.adcs.SPIN_LAW"):
        load_scenario("adcs", settings=["control.adcs.SPIN_LAW=SPIN_FAST"])
    with pytest.raises(ScenarioError, match="control.adcs.target_q_bn"):
        load_scenario("adcs", settings=["control.adcs.target_q_bn=[1, 1, 0, 0]"])
    with pytest.raises(ValueError, match="unknown attitude-controller parameter 'K_Q'"):
        AdcsLaw(params={"K_Q": 1.0})


def test_adcs_scenario_target_is_the_start_up_sequence_s():
    """The adcs scenario's control.adcs.target_q_bn is what deployments/adcs_ref/startup.seq commands."""
    import pathlib

    seq = pathlib.Path(__file__).parents[3] / "deployments" / "adcs_ref" / "startup.seq"
    line = next(x for x in seq.read_text().splitlines() if "SET_TARGET_QUATERNION" in x and not x.startswith(";"))
    q = tuple(float(x) for x in line.split()[-4:])
    assert load_scenario("adcs").control.adcs.target_q_bn == q


def test_without_wheels_it_points_on_the_magnetorquers():
    """No wheels: the law keeps the component's magnetorquer-only pointing (FIELD_STEERING), never a wheel."""
    plant = Plant(load_scenario("default"))
    law = make_law("adcs", plant)
    assert law.wheels is False and law.params["MAG_POINTING_LAW"] == "FIELD_STEERING"


def test_gain_is_refused_and_a_bad_step_too():
    sc = load_scenario("adcs")
    with pytest.raises(LawError, match="control.adcs"):
        run(sc, law="adcs", gain=2.0, duration_s=1.0)
    sc = load_scenario("adcs", settings=["dynamics_step_s=0.03", "control.period_s=0.03", "control.sense_settle_s=0"])
    with pytest.raises(LawError, match="must divide it"):
        run(sc, law="adcs", duration_s=1.0)


def test_cli_flies_it_and_reports_the_modes(tmp_path):
    """`fprime-lite sim adcs --law adcs` (the same main): summary with the mode transitions."""
    assert main(["adcs", "--law", "adcs", "--duration", "20", "--out", str(tmp_path)]) == 0
    s = json.loads((tmp_path / "summary.json").read_text())
    assert s["law"] == "adcs" and s["final_mode"] == "DETUMBLE"
    assert s["control_mode_transitions"] == [{"t_s": 0.1, "mode": "DETUMBLE", "reason": "AUTO_START"}]
    assert s["control_cycles"] == 200


def test_pointing_statistics_skip_the_first_tenth():
    assert pointing_statistics([]) is None
    s = pointing_statistics([100.0] + [float(i) for i in range(1, 10)])
    assert s == {"median": 5.0, "p95": pytest.approx(8.6), "max": 9.0, "samples": 9}
    assert math.isnan(AdcsLaw().true_pointing_error_deg((1.0, 0.0, 0.0, 0.0)))
    pooled = pointing_statistics([100.0] + [0.02] * 9, sample_interval_s=0.5)
    assert pooled["window_s"] == 4.5 and pooled["time_above_s"]["0.01"] == 4.5 and pooled["time_above_s"]["0.05"] == 0


def test_force_mode_holds_a_mode_as_force_mode_does():
    """ADCS-077: `control.adcs.force_mode` sends one FORCE_MODE at `force_at_s` and holds the mode (no AUTO
    trigger moves it: a 25 °/s tumble stays in SPIN_STABLE, where AUTO would detumble); POINTING is refused
    without attitude knowledge (at 25 °/s the star tracker gives no fix: the law stays IDLE, the command is
    not retried); a mode that does not exist is refused at the scenario key and by the law."""
    tumble = "initial.rate.magnitude_deg_s=25"
    spin = ["control.adcs.force_mode=SPIN_STABLE", "control.adcs.force_at_s=2"]
    summary = run(load_scenario("adcs", settings=[tumble, *spin]), law="adcs", duration_s=20.0).summary
    assert [(t["mode"], t["t_s"]) for t in summary["control_mode_transitions"]] == [("SPIN_STABLE", 2.0)]
    point = ["control.adcs.force_mode=POINTING", "control.adcs.force_at_s=2"]
    summary = run(load_scenario("adcs", settings=[tumble, *point]), law="adcs", duration_s=20.0).summary
    assert summary["control_mode_transitions"] == []
    with pytest.raises(ScenarioError, match="control.adcs.force_mode"):
        load_scenario("adcs", settings=["control.adcs.force_mode=SAFE"])
    with pytest.raises(ValueError, match="force_mode 'SAFE'"):
        AdcsLaw(force_mode="SAFE")


def test_commands_act_from_the_first_cycle_after_their_time():
    """ADCS-079: a FORCE_MODE sent at 2.0 s (a cycle's own instant) acts from the cycle at 2.1 s, its transition
    stamped 2.0 s as the component's event is; a target change at 1.05 s is in place at the 1.1 s cycle and clears
    the error integral; changes out of order, non-unit targets and malformed entries are refused at the key."""
    q_new = (0.7071067811865476, 0.0, 0.0, 0.7071067811865476)
    law = AdcsLaw(force_mode="SPIN_STABLE", force_at_s=2.0, target_changes=[(1.05, q_new)])
    plant = Plant(load_scenario("adcs", settings=["initial.rate.magnitude_deg_s=3"]))
    io = PlantIo(plant)
    seen = {}
    law.integrator.state = (1.0, 2.0, 3.0)  # as if pointing had integrated an error
    for _ in range(int(round(2.2 / law.tick_s))):
        t_us = io.now_us()
        law.tick(io)
        seen[t_us] = (law.mode, law.target, law.integrator.state)
        plant.step(law.tick_s)
    assert seen[1_000_000][1:] == (None, (1.0, 2.0, 3.0))
    assert seen[1_100_000][1:] == (q_new, (0.0, 0.0, 0.0))
    assert seen[2_000_000][0] == "IDLE" and seen[2_100_000][0] == "SPIN_STABLE"
    assert law.transitions == [(2.0, "SPIN_STABLE", "COMMAND")]
    with pytest.raises(ValueError, match="not a unit quaternion"):
        AdcsLaw(target_changes=[(1.0, (1.0, 1.0, 0.0, 0.0))])
    with pytest.raises(ValueError, match="time order"):
        AdcsLaw(target_changes=[(2.0, q_new), (1.0, q_new)])
    for bad, says in (("[[1, 1, 0, 0]]", "expected \\[t_s, q0, q1, q2, q3\\]"),
                      ("[[-1, 1, 0, 0, 0]]", "negative"),
                      ("[[5, 1, 0, 0, 0], [4, 1, 0, 0, 0]]", "time order"),
                      ("[[5, 1, 1, 0, 0]]", "unit quaternion"),
                      ("7", "expected a list")):
        with pytest.raises(ScenarioError, match=f"control.adcs.target_changes.*{says}"):
            load_scenario("adcs", settings=[f"control.adcs.target_changes={bad}"])
    with pytest.raises(ScenarioError, match="control.adcs.target_q_bn.*unit quaternion"):
        load_scenario("adcs", settings=["control.adcs.target_q_bn=[1, 1, 0, 0]"])
    scenario = load_scenario("adcs", settings=["control.adcs.target_changes=[[300, 0, 1, 0, 0]]"])
    assert make_law("adcs", Plant(scenario)).target_changes == ((300_000_000, (0.0, 1.0, 0.0, 0.0)),)
