"""F´ standard services (Svc), one module per component."""
