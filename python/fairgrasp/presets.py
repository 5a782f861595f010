"""Preset names as a caller gives them: a renamed preset's old name (``"seed"``, now
``"sector"``) still works for now, with a ``DeprecationWarning`` naming the current one; the
table of old names is the Rust one (``RENAMED_PRESETS`` in ``env/src/config/presets.rs``)."""

import os
import sys
import warnings

from . import _native

_PACKAGE = os.path.dirname(os.path.abspath(__file__)) + os.sep


def _caller_stacklevel():
    """``warnings.warn``'s stacklevel, seen from ``current_preset``, of the first frame outside
    this package: the warning names the caller's line, not fairgrasp's."""
    frame, level = sys._getframe(2), 2
    while frame is not None and os.path.abspath(frame.f_code.co_filename).startswith(_PACKAGE):
        frame, level = frame.f_back, level + 1
    return level


def current_preset(name):
    """The current name of the preset ``name``: an old name gives the new one and a
    ``DeprecationWarning``; a current name, a .toml path, None or anything else comes back as
    it is."""
    if not isinstance(name, str):
        return name
    current, note = _native.current_preset_name(name)
    if note is not None:
        warnings.warn(note, DeprecationWarning, stacklevel=_caller_stacklevel())
    return current
