"""Package discovery for the three source roots mapped in pyproject.toml.

setuptools' automatic discovery cannot rename directories (compiler/ is installed as `rfc`), so
the sub-packages of each root are listed here under their installed names.
"""

from setuptools import find_packages, setup

ROOTS = {"rfc": "compiler", "rfc.runtime": "runtime", "rfc.lib": "lib"}

setup(
    packages=[
        *ROOTS,
        *(f"{name}.{sub}" for name, folder in ROOTS.items() for sub in find_packages(folder)),
    ],
)
