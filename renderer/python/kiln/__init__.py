"""kiln: renders glTF 2.0 assets with Embree and Whitted shading; AOVs as NumPy arrays.

kiln.render(asset, **options) renders once; kiln.options() lists the options (those of
`kiln render`). `python -m kiln render ...` runs the command line installed with the package.
"""
from ._kiln import *  # noqa: F401,F403 (the module's functions, Result and the error classes)
from ._kiln import __version__  # noqa: F401
