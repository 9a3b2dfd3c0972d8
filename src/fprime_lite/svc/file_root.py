"""The root directory a file service is confined to (FileUplink, FileDownlink, FileManager).

Without a root of its own (``root=None``) a service starts in the working directory at
construction; ``fprime-lite run`` then gives it the run's folder (:meth:`FileRoot.set_default_root`).
At start-up the deployment calls :meth:`FileRoot.clean_temporary_files`.
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
        """The directory every path lies in (symbolic links resolved)."""
        return self._confinement.root

    def set_default_root(self, folder) -> None:
        """Use ``folder`` as the root unless one was given at construction (the runner passes the
        run's folder)."""
        if not self._root_given:
            self._confinement = Confinement(folder)

    def clean_temporary_files(self) -> list[str]:
        """Start-up: remove the temporary files that a killed process left under the root."""
        removed = clean_temporary_files(self.root_path, recursive=True)
        if removed:
            log.info("%s: removed %d temporary file(s) left under %s", self.name, len(removed), self.root_path)
        return removed
