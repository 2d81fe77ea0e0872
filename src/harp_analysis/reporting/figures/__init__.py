"""The figures, one module per family (every figure is drawn here)."""
