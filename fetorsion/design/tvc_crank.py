"""The crank of a network against IACS UR M53 in each TVC configuration (docs/propulsion-tvc.md).

Where a network holds a fetorsion crank description as a lumped part (``[[chain.cranks]]``; a network on
the condensed crank is run as that crank's own report in its driveline), the TVC judges that crank by the rule the crank alone is judged by: UR M53 (:func:`.m53.run_m53_crank`),
its torsion the network's own synthesised half-range torque through each fillet's section in the
configuration (the driveline, couplings and propeller change it), its bending the crank's rod forces
at the rated speed (the same in every configuration). The network's response names the crank's
stations ``<crank>.<label>`` of its lumped partition; each fillet carries the torque of the spring of
that partition between the anchors around it (:func:`.stress.fillet_springs`), which is the network's
section between those two stations.

Normal running decides the crank's verdict, as it decides the shafts' continuous limits; a misfire's,
a failed damper's or a tolerance end's Q below the required one is a restriction for that operation,
said beside it.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import replace

import numpy as np

from ..errors import FetorsionError
from ..lumped_model.lumped import lumped
from .m53 import M53Result, run_m53_crank
from .stress import fillet_springs, fillets_of
from .tvc_cases import TVCCase


def network_fillet_torques(case: TVCCase):
    """(crank, fillets, half-range torque (speeds, fillets) N·m) of the network's crank in a configuration,
    the crank carrying the network's ``[excitation]`` (its rod forces then those the torques come from).

    Raises FetorsionError where the crank does not drive the network (the network's own ``[engine]``
    places the cylinders) or the response has no section between two of the crank's anchors."""
    part = case.network.cranks[0]
    if not part.drives or case.network.excitation is None:
        raise FetorsionError("the network's own [engine] and [excitation] drive it, not the crank description's "
                             "pins, so the crank's rod forces are not the network's")
    chain = lumped(part.crank, part.partition, part.web_method)
    fillets = fillets_of(part.crank)
    springs = fillet_springs(fillets, chain.positions_m)
    names = [f"{part.name}.{a}-{part.name}.{b}" for a, b in zip(chain.labels, chain.labels[1:])]
    labels = list(case.response.section_labels)
    missing = sorted({names[k] for k in springs if names[k] not in labels})
    if missing:
        raise FetorsionError(f"the crank's sections {', '.join(missing)} are not in the network's response")
    columns = [labels.index(names[k]) for k in springs]
    crank = replace(part.crank, excitation=case.network.excitation)
    return crank, fillets, np.asarray(case.response.section_torque_nm)[:, columns]


def crank_m53(cases: Sequence[TVCCase]) -> tuple[list[tuple[str, M53Result]], str]:
    """(each configuration's name and its crank's M53, a note: why none was computed, or "") for the
    configurations of a network with a fetorsion crank; ([], "") without one."""
    cases = [c for c in cases if c is not None]
    if not cases or not cases[0].network.cranks:
        return [], ""
    out = []
    try:
        for case in cases:
            crank, fillets, torque = network_fillet_torques(case)
            out.append((case.name, run_m53_crank(crank, fillets, torque, case.response.rpm)))
    except FetorsionError as e:
        return [], f"the crank's M53 not computed: {e}"
    return out, ""
