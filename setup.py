"""Everything but one file is declared in pyproject.toml: this puts ``goalagent-gymnasium.pth``
(robot/gym_plugin.py says why) into the site-packages directory of the Python that installs
goalagent, which setuptools' static ``data-files`` cannot name (its path holds the version).

Editable installs (``pip install -e``, as scripts/setup.sh does) need one more step:
setuptools' ``editable_wheel`` asks the distribution for ``has_data``, which it does not have
(its method is ``has_data_files``), and so never installs data files; ``EditableWithData``
installs them.
"""

import os
import sys
import sysconfig

from setuptools import setup
from setuptools.command.editable_wheel import editable_wheel

SITE_PACKAGES = os.path.relpath(sysconfig.get_paths()["purelib"], sys.prefix)


class EditableWithData(editable_wheel):
    """An editable wheel that carries the data files too."""

    def run(self):
        if self.distribution.has_data_files() and not hasattr(self.distribution, "has_data"):
            self.distribution.has_data = self.distribution.has_data_files
        super().run()


setup(data_files=[(SITE_PACKAGES, ["robot/goalagent-gymnasium.pth"])],
      cmdclass={"editable_wheel": EditableWithData})
