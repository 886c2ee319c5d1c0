"""Who may log in to the OPC UA server, and who may write.

Anonymous clients read (unless ``anonymous = false``). With users
configured, a client that logs in with a user name and password may also
write the variables ``writable`` names; an anonymous one may not. Without
users, writes to those variables are open to every client (the endpoint is
on 127.0.0.1 unless configured otherwise).

Passwords are given in the configuration (``users = { operator = "..." }``)
or in a users file (``users_file``: a TOML file with a ``[users]`` table),
each either as the password itself or, better, as a PBKDF2 hash made by

    python -m softplc.runtime.surfaces.opcua.users PASSWORD
    pbkdf2_sha256$600000$<salt>$<hash>

(hashlib's PBKDF2-HMAC-SHA256, 600,000 iterations, as OWASP recommends;
checked in constant time).
"""

from __future__ import annotations

import base64
import hashlib
import hmac
import logging
import os
import sys
import tomllib
from pathlib import Path

from asyncua import ua
from asyncua.crypto.permission_rules import User, UserRole
from asyncua.server.user_managers import UserManager

log = logging.getLogger("softplc.surfaces.opcua")

SCHEME = "pbkdf2_sha256"
ITERATIONS = 600_000


class UsersError(ValueError):
    """A users file that cannot be read: the message names the file and the problem."""


def hash_password(password: str, iterations: int = ITERATIONS, salt: bytes | None = None) -> str:
    salt = os.urandom(16) if salt is None else salt
    digest = hashlib.pbkdf2_hmac("sha256", password.encode(), salt, iterations)
    return f"{SCHEME}${iterations}${_b64(salt)}${_b64(digest)}"


def check_password(stored: str, password: str) -> bool:
    """password against stored (a hash made by hash_password, or the password itself)."""
    if not stored.startswith(SCHEME + "$"):
        return hmac.compare_digest(stored.encode(), password.encode())
    try:
        _scheme, iterations, salt, digest = stored.split("$")
        expected = base64.b64decode(digest)
        got = hashlib.pbkdf2_hmac("sha256", password.encode(), base64.b64decode(salt), int(iterations))
    except ValueError:
        return False
    return hmac.compare_digest(got, expected)


def _b64(data: bytes) -> str:
    return base64.b64encode(data).decode("ascii")


def load_users(users: dict, users_file: Path | None) -> dict:
    """The users of the configuration and of its users file (name -> password or hash)."""
    out = dict(users)
    if users_file is not None:
        try:
            data = tomllib.loads(Path(users_file).read_text(encoding="utf-8"))
        except (OSError, ValueError) as exc:  # TOMLDecodeError, UnicodeDecodeError (config/servers.py checks first)
            raise UsersError(f"[opcua] users_file {users_file}: {exc}") from None
        table = data.get("users")
        if not isinstance(table, dict) or not all(isinstance(v, str) for v in table.values()):
            raise UsersError(f'[opcua] users_file {users_file}: expected a [users] table of name = "hash"')
        out.update(table)
    return out


class PlcUsers(UserManager):
    """asyncua's user manager: a known name with its password is a User of
    that name, no name a User without one (asyncua's role Anonymous may not
    even browse), anything else is refused.

    With ``encrypted_only`` (the certificate mode) a session on a channel
    without security is refused (BadSecurityModeInsufficient) whoever asks:
    asyncua lists only the encrypted endpoint but lets any client open an
    unencrypted channel (for discovery, as OPC UA requires) and, on it, a
    session that reads everything. Such a channel carries no client
    certificate; an encrypted one always does."""

    def __init__(self, users: dict, anonymous: bool = True, encrypted_only: bool = False) -> None:
        self.users = users
        self.anonymous = anonymous
        self.encrypted_only = encrypted_only

    def get_user(self, iserver, username=None, password=None, certificate=None) -> User | None:
        if self.encrypted_only and not certificate:
            log.warning("opcua: a session without encryption refused (certificate mode)")
            raise ua.uaerrors.BadSecurityModeInsufficient
        if username is None:
            return User(role=UserRole.User) if self.anonymous else None
        stored = self.users.get(username)
        if stored is None or password is None or not check_password(stored, password):
            log.warning("opcua: login refused for user %r", username)
            return None
        return User(role=UserRole.User, name=username)


def main(argv: list | None = None) -> int:
    args = sys.argv[1:] if argv is None else argv
    if len(args) != 1:
        print("usage: python -m softplc.runtime.surfaces.opcua.users PASSWORD", file=sys.stderr)
        return 2
    print(hash_password(args[0]))
    return 0


if __name__ == "__main__":
    sys.exit(main())
