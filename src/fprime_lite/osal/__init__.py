"""F´'s Os layer: what the framework needs of the operating system (atomic file writes, output folders)."""
