"""Exceptions raised by the contactsim client."""
import builtins

from .protocol import CODE_NAMES  # reply_t code -> name


class CommandError(Exception):
    """The server rejected a command.

    ``code`` is the reply_t code (int, e.g. ``reply_t.INVALID_ARGUMENT``),
    ``code_name`` its name, ``message`` the server's message (it names the
    field and the value) and ``reply`` the whole reply (None on a timeout).
    """

    def __init__(self, message, code=None, reply=None):
        super().__init__(message)
        self.message = message
        self.code = code
        self.code_name = CODE_NAMES.get(code, str(code)) if code is not None else None
        self.reply = reply

    def __str__(self):
        if self.code_name is None:
            return self.message
        return "%s: %s" % (self.code_name, self.message)


class TimeoutError(CommandError, builtins.TimeoutError):
    """No reply (or no STATE/STATUS) arrived in time.

    A subclass of both CommandError and the builtin TimeoutError, so either
    ``except contactsim.CommandError`` or ``except TimeoutError`` catches it;
    ``code`` and ``reply`` are None.
    """

    def __init__(self, message):
        CommandError.__init__(self, message)


class AuthKeyError(ValueError):
    """An auth key file that cannot be read or holds too short a key
    (docs/protocol.md, "Authentication"); the message names the file."""
