"""Where the server binary and the repository's config are, as
contactsim/_lcmtypes.py finds the generated types."""
import os
from pathlib import Path


def repo_root():
    return Path(__file__).resolve().parents[4]


def build_dir():
    """$CONTACTSIM_BUILD_DIR, else the repository's build/ (as _lcmtypes finds it)."""
    env = os.environ.get("CONTACTSIM_BUILD_DIR")
    if env:
        return Path(env).resolve()
    return repo_root() / "build"


def server_binary():
    return Path(os.environ.get("CONTACTSIM_SERVER") or build_dir() / "bin" / "contactsim-server")

