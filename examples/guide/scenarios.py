"""Scenarios: presets, changes, files (docs/guide/scenarios.md)."""

from pathlib import Path

import landing
from landing.scenarios import Scenario, preset

# Every preset is a Scenario: plant, law, reference, disturbance, initial state, dispersion and
# run options in one object, printable and comparable.
s = preset("mars_nominal")
print(f"{s.name}: {type(s.plant).__name__} under {type(s.controller).__name__}, "
      f"{s.options.t_final:g} s at {s.options.dt:g} s")

# A change is a new scenario (each part is validated again): a dict changes some parameters of a
# part and keeps the others.
bolder = s.replace(controller={"alpha1": 6.0}, t_final=45.0)
print(f"alpha1 {s.controller.alpha1} -> {bolder.controller.alpha1}, t_final {bolder.options.t_final:g} s")

# A scenario is a TOML file and back, the same scenario.
Path("bolder.toml").write_text(bolder.to_toml(), encoding="utf-8")
again = Scenario.load("bolder.toml")
print("the file's first lines:")
print("\n".join("  " + line for line in Path("bolder.toml").read_text(encoding="utf-8").splitlines()[1:8]))
same = again.simulate().metrics["settle_time"] == bolder.simulate().metrics["settle_time"]
print(f"read back and run: the same landing time: {bool(same)}")

# A bad value is refused when the scenario is made, naming the part, the parameter and the rule.
try:
    s.replace(controller={"q1": 1.5})
except landing.ParameterError as e:
    print(f"refused: {e}")
