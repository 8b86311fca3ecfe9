"""Long runs continued from their last checkpoint."""

from __future__ import annotations

import json
import os
from typing import Any, Dict, Union

from . import _native, _progress


def resume(dir: Union[str, "os.PathLike[str]"], progress: _progress.Request = False) -> Dict[str, Any]:
    """Continues the run whose checkpoint is in ``dir`` (written by
    ``Problem.solve(dir=..., checkpoint_every=...)`` or ``marsden run --checkpoint-every``) to
    its end, as ``marsden resume`` does: the files it leaves in ``dir`` are byte for byte those
    of the uninterrupted run (the wall-clock times of ``summary.json`` aside). A sweep's
    checkpoint (``marsden run`` on a file with ``[sweep]`` and ``checkpoint_every``) resumes the
    sweep: the members in its table are kept, the others run.

    Returns the run's (or the sweep's) ``summary.json`` as a dictionary; its ``"status"`` says how the run ended
    (``"failed"`` with ``"error"`` if a step failed). Raises :class:`marsden.ProblemError`,
    with nothing changed in ``dir``, if there is no checkpoint, if it is damaged or of a format
    this version cannot read, or if the problem file changed since.
    """
    text = _native.resume(os.fspath(dir), _progress.callback(progress))
    return json.loads(text)
