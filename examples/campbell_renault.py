"""
Campbell diagram of the Renault 21
==================================

Which resonances of the Renault 21 crank matter: the Campbell crossings ranked by severity."""

from pathlib import Path

import fetorsion
from fetorsion.excitation.campbell import most_severe

# The repository's root, so that the script runs from any folder (the documentation builds the
# gallery from inside examples/).
ROOT = Path(fetorsion.__file__).resolve().parents[1]

crank = fetorsion.load(ROOT / "geometry/renault21.toml")
res = fetorsion.run_campbell(crank)
print(res.table())
worst = most_severe(res.crossings, 1)[0]
print(f"worst: order {worst.order:g} at {worst.rpm:.0f} rpm, {worst.severity:.3f} deg at the pulley")

# The Campbell diagram: the mode frequencies against speed, the engine orders as rays, each
# crossing in the operating range marked by its severity.
res.plot()
