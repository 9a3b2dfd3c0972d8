"""Plant physics of the simulated PROVES 1U CubeSat (no F' framework import anywhere here).

Modules: :mod:`.vec` (plain-float vectors/quaternions, the quaternion convention),
:mod:`.attitude` (rigid body, RK4), :mod:`.orbit`, :mod:`.field`, :mod:`.torques`,
:mod:`.sensors`, :mod:`.coils`, :mod:`.scenario`, :mod:`.plant`, :mod:`.laws`, :mod:`.runner`,
:mod:`.wheels` (reaction wheels and their coupled RK4 step), :mod:`.star_tracker`,
:mod:`.frames` (the orbit frame, q_BO), :mod:`.truth` (the ADCS truth columns).
"""


from typing import Any

__all__ = ["Plant", "Scenario", "ScenarioError", "load_scenario", "parse_scenario", "scenario_from_dict"]


def __getattr__(name: str) -> Any:
    """The package's names, imported when first read: importing one light module of the package
    (``detumble.sim.coils``) does not import the plant and the scenario schema (issue 30: an FPP
    model's load + bind imports the drivers, which need the simulation's types, not the plant)."""
    if name == "Plant":
        from detumble.sim.plant import Plant

        return Plant
    if name in __all__:
        from detumble.sim import scenario

        return getattr(scenario, name)
    raise AttributeError(f"module 'detumble.sim' has no attribute {name!r}")
