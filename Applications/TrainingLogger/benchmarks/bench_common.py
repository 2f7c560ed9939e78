"""What the logger's benchmark scripts share: their --name=value options."""

import sys


def arg(name, default):
    """The value of --name=VALUE on the command line, of default's type, or default."""
    for a in sys.argv[1:]:
        if a.startswith("--" + name + "="):
            return type(default)(a.split("=", 1)[1])
    return default
