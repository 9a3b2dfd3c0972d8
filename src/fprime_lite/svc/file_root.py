"""The root directory a file service is confined to (FileUplink, FileDownlink, FileManager).

Without a root of its own (``root=None``) a service starts in the working directory at
construction; ``fprime-lite run`` then gives it the run's folder (:meth:`FileRoot.set_default_root`).
At start-up the deployment calls :meth:`FileRoot.clean_temporary_files` once for each distinct root
(the three services usually share one; it is swept recursively).
"""

from __future__ import annotations

import logging
import os

from fprime_lite.osal.atomic import clean_temporary_files
from fprime_lite.osal.confine import Confinement

__all__ = ["FileRoot"]

log = logging.getLogger("fprime_lite")


class FileRoot:
    """Mixin of the file services: the confinement to one root and its start-up clean-up."""

    name: str
    _confinement: Confinement
    _root_given: bool

    def _init_root(self, root) -> None:
        self._root_given = root is not None
        self._confinement = Confinement(root if root is not None else os.getcwd())

    @property
    def root_path(self) -> str:
        """The directory relative paths resolve against (symbolic links resolved): the root every
        path lies in, unless ``set_default_root`` was given a wider ``confine_to``."""
        return self._confinement.base

    @property
    def confinement_root(self) -> str:
        """The directory every path must lie in (symbolic links resolved)."""
        return self._confinement.root

    def set_default_root(self, folder, confine_to=None, board: bool = False) -> None:
        """Use ``folder`` as the root unless one was given at construction (the runner passes the
        run's folder). ``confine_to``: a wider folder holding ``folder`` that paths may reach
        (``run --file-root``); relative paths still resolve against ``folder``. ``board``: ``folder``
        stands in for the board's ``/`` (``run --board-root``): absolute paths are taken inside it."""
        if not self._root_given:
            if board:
                self._confinement = Confinement(folder, board=True)
            else:
                self._confinement = Confinement(confine_to if confine_to is not None else folder, base=folder)

    def clean_temporary_files(self) -> list[str]:
        """Start-up: remove the temporary files that a killed process left under the root (the
        service's own folder, never a wider ``confine_to`` other runs share)."""
        removed = clean_temporary_files(self.root_path, recursive=True)
        if removed:
            log.info("%s: removed %d temporary file(s) left under %s", self.name, len(removed), self.root_path)
        return removed
