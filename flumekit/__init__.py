"""flumekit: wave-flume experiments on wave energy converters, from raw recordings to figures."""

__version__ = "0.1.0"

from flumekit.errors import FlumekitError, InputError  # noqa: F401 - public re-export
