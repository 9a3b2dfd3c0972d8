"""FPP models in: F´ component and topology definitions bound to Python implementations (docs/fpp.md)."""
