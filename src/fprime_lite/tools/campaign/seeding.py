"""Run identity: the run id and the random streams of a run, from one master seed.

A run is identified by what it *is* — the campaign's run section, its grid point and its seed
index — never by when or where it executes. From that identity:

- the run's seed sequence is ``SeedSequence(master_seed, spawn_key=H(point, seed_index))`` where
  ``H`` is four 32-bit words of a SHA-256 of the canonical JSON of the point;
- the simulator seed (sensor noise) is its first 32-bit word;
- each dispersed key draws from its own child stream (the key's hash appended to the spawn key), so
  adding a dispersion to a campaign leaves the others' values unchanged;
- the run id is 16 hex digits of a SHA-256 over the run section, the point and the seed.
"""

from __future__ import annotations

import hashlib
import json

import numpy as np

__all__ = ["canonical", "run_seed_sequence", "simulator_seed", "key_generator", "run_id"]


def canonical(obj) -> str:
    """Deterministic JSON (sorted keys, no spaces; floats as Python's shortest repr)."""
    return json.dumps(obj, sort_keys=True, separators=(",", ":"), allow_nan=True, default=str)


def _words(text: str, n: int) -> tuple[int, ...]:
    digest = hashlib.sha256(text.encode("utf-8")).digest()
    return tuple(int.from_bytes(digest[4 * i:4 * i + 4], "little") for i in range(n))


def run_seed_sequence(master_seed: int, point: dict, seed_index: int, *,
                      point_json: str | None = None) -> np.random.SeedSequence:
    """The seed sequence of the run at grid ``point`` with seed index ``seed_index``
    (``point_json``: ``canonical(point)`` when the caller has it already)."""
    text = f"[{point_json if point_json is not None else canonical(point)},{int(seed_index)}]"
    return np.random.SeedSequence(int(master_seed), spawn_key=_words(text, 4))


def simulator_seed(seq: np.random.SeedSequence) -> int:
    """The run's simulator seed: a 32-bit integer drawn from its seed sequence."""
    return int(seq.generate_state(1, np.uint32)[0])


def key_generator(seq: np.random.SeedSequence, key: str) -> np.random.Generator:
    """The generator that draws the dispersed value of ``key`` in this run."""
    child = np.random.SeedSequence(seq.entropy, spawn_key=tuple(seq.spawn_key) + _words(key, 2))
    return np.random.default_rng(child)


def run_id(run_section: dict, point: dict, seed: int, *, run_json: str | None = None,
           point_json: str | None = None) -> str:
    """16 hex digits identifying a run by its parameters and seed: a SHA-256 of the canonical JSON
    ``{"point": …, "run": …, "seed": …}`` (``run_json`` / ``point_json``: the canonical JSON of
    ``run_section`` / ``point`` when the caller has them already — the same text, built once)."""
    text = (f'{{"point":{point_json if point_json is not None else canonical(point)},'
            f'"run":{run_json if run_json is not None else canonical(run_section)},"seed":{int(seed)}}}')
    return hashlib.sha256(text.encode()).hexdigest()[:16]
