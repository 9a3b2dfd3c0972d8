"""Plant physics of the simulated PROVES 1U CubeSat (no F' framework import anywhere here).

Modules: :mod:`.vec` (plain-float vectors/quaternions, the quaternion convention),
:mod:`.attitude` (rigid body, RK4), :mod:`.orbit`, :mod:`.field`, :mod:`.torques`,
:mod:`.sensors`, :mod:`.coils`, :mod:`.scenario`, :mod:`.plant`, :mod:`.laws`, :mod:`.runner`,
:mod:`.wheels` (reaction wheels and their coupled RK4 step), :mod:`.star_tracker`,
:mod:`.frames` (the orbit frame, q_BO), :mod:`.truth` (the ADCS truth columns).
"""

from detumble.sim.plant import Plant
from detumble.sim.scenario import Scenario, ScenarioError, load_scenario, parse_scenario, scenario_from_dict

__all__ = ["Plant", "Scenario", "ScenarioError", "load_scenario", "parse_scenario", "scenario_from_dict"]
