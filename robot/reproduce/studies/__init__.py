"""The studies, one module each (``NAME`` with ``-`` as ``_``, defining ``STUDY``); the
helpers several of them share are in ``common/``."""
