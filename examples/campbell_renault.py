"""Which resonances of the Renault 21 crank matter: the Campbell crossings ranked by severity."""

import fetorsion

crank = fetorsion.load("geometry/renault21.toml")
res = fetorsion.run_campbell(crank)
print(res.table())
worst = max((c for c in res.crossings if c["in_range"]), key=lambda c: c["severity"])
print(f"worst: order {worst['order']:g} at {worst['rpm']:.0f} rpm, {worst['severity']:.3f} deg at the pulley")
