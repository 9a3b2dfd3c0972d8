"""Control laws and flight arithmetic as plain Python: no framework import."""
