"""Length units accepted in description files; everything inside fetorsion is SI."""

LENGTH_UNITS = {"m": 1.0, "cm": 1e-2, "mm": 1e-3, "in": 0.0254}
