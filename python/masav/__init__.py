"""masav: one kernel set on the CPU reference, Vulkan and CUDA, cross-checked against each other.

The extension masav._masav holds everything; see docs/python.md.
"""
from ._masav import *  # noqa: F401,F403
from ._masav import __version__, constants  # noqa: F401
