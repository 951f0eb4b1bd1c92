"""Files on disk, for every layer: written atomically, read only when regular and bounded.

Every file goalagent writes (saved beliefs, traces, learners and models, the known-object
database, reproduction pages and figures, environment pictures, videos) goes through
:func:`write_atomically`, :class:`AtomicFile` or :func:`atomic_path`; every untrusted file
it reads whole (program files, can files, JSON stores) through :func:`read_bounded`; where
the user's cache folder is, :func:`ondisk.cache.cache_folder` says. This
package imports nothing of goalagent's, sim's, behaviours' or robot's, so each of those
layers may use it (pyproject's import-linter contract keeps it the lowest layer).

Hand-written because no well-kept library does the whole job: python-atomicwrites was
archived in 2022 and neither fsyncs the folder nor keeps the mode; the younger ones do not
refuse devices, FIFOs or links as targets, which is what keeps a save from replacing
``/dev/full`` or writing through a planted link.
"""

from ondisk.atomic import AtomicFile, TargetError, atomic_path, check_target, write_atomically
from ondisk.bounded import read_bounded

__all__ = ["AtomicFile", "TargetError", "atomic_path", "check_target", "read_bounded",
           "write_atomically"]
