"""Issue 54: a long command says where it is: each stage as it starts, the share of the expected
time done, the time so far and the time left at that pace."""

from __future__ import annotations

import pytest

from fetorsion.io import Stages


def test_each_stage_says_its_share_and_the_time_left_at_the_pace_so_far():
    """Stages of 3, 9, 8 s expected: at the third, 12 of 20 are done (60 %); 6 s spent gives
    6 · 0.4 / 0.6 = 4 s left. The first stage has no pace yet and says no time left."""
    said, now = [], [100.0]
    stages = Stages("modal", {"meshing": 3.0, "assembling": 9.0, "factorising": 8.0}, said.append)
    stages.clock = lambda: now[0]
    stages.start = 100.0
    stages("meshing")
    now[0] = 106.0
    stages("factorising")
    assert said == ["modal: meshing (stage 1 of 3, 0 % done, 0 s)",
                    "modal: factorising (stage 3 of 3, 60 % done, 6 s, about 4 s left)"]
    with pytest.raises(ValueError, match="'solving' is not one of"):
        stages("solving")
