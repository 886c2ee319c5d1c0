"""The sections of the servers a running PLC offers: [web] (the monitor
page), [opcua] (an OPC UA server) and [modbus_server] (a Modbus TCP server
for HMIs). Each listens on 127.0.0.1 unless `host` says otherwise; another
host is allowed but logged as a warning, since it opens the PLC to the
network. `writable` lists the variables the surface may write and force
(fnmatch patterns over ST paths and addresses: "Main.*", "%QX*", "*").

    [web]
    port = 8080                   # host = "127.0.0.1", writable = ["*"]

    [opcua]
    port = 4840
    writable = ["Main.Setpoint"]  # read-only unless listed

    [modbus_server]
    port = 5020                   # writable = ["%Q*", "%M*"], unit = 0 (answers any unit id),
                                  # max_connections = 32
"""

from __future__ import annotations

import dataclasses
import ipaddress
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Annotated, Any

from pydantic import Field, PlainValidator, ValidationInfo
from pydantic_core import PydanticCustomError

from .relations import Relations
from .section import Section
from .values import DURATION_EXAMPLES, Model, existing_file, fail, int_range, is_host, positive_duration

LOOPBACK = "127.0.0.1"


def _host(value) -> str:
    if isinstance(value, str) and is_host(value):
        return value
    raise fail('a host name or address to listen on, such as "127.0.0.1" or "0.0.0.0"', value)


def _patterns(value) -> tuple:
    if isinstance(value, list) and all(isinstance(v, str) and v.strip() for v in value):
        return tuple(v.strip() for v in value)
    raise fail('an array of variable paths or patterns such as ["Main.Setpoint", "%QX*", "*"]', value)


def _users(value) -> dict:
    if isinstance(value, dict) and all(isinstance(k, str) and isinstance(v, str) and v for k, v in value.items()):
        return dict(value)
    raise fail('a table of user names and passwords (or hashes) such as { operator = "pbkdf2_sha256$..." }', value)


def _optional_file(value, info: ValidationInfo) -> Path | None:
    if value is None:
        return None
    if not isinstance(value, str) or not value.strip():
        raise fail('the path of a file such as "pki/server.der"', value)
    return existing_file(value, info)


#: a users file larger than this is no list of users
USERS_FILE_MAX = 1 << 20


def _users_file(value, info: ValidationInfo) -> Path | None:
    """An existing TOML file with a [users] table of name = "password or
    hash", read here so that a bad one is the key's error, not the server's."""
    path = _optional_file(value, info)
    if path is None:
        return None
    try:
        with open(path, "rb") as f:
            data = f.read(USERS_FILE_MAX + 1)
    except OSError as exc:
        raise PydanticCustomError(
            "config", "cannot read {path}: {why}", {"path": str(path), "why": exc.strerror or str(exc)}
        ) from None
    why = None
    if len(data) > USERS_FILE_MAX:
        why = f"larger than {USERS_FILE_MAX >> 20} MB"
    else:
        try:
            table = tomllib.loads(data.decode("utf-8")).get("users")
        except UnicodeDecodeError as exc:
            why = f"not UTF-8 text (byte {exc.start}); a TOML file is UTF-8"
        except (ValueError, RecursionError) as exc:  # TOMLDecodeError, a number too long, nesting too deep
            why = f"invalid TOML: {exc}" if isinstance(exc, tomllib.TOMLDecodeError) else "invalid TOML"
        else:
            if not isinstance(table, dict) or not all(isinstance(v, str) and v for v in table.values()):
                why = 'expected a [users] table of name = "password or hash"'
    if why is not None:
        raise PydanticCustomError("config", "{path}: {why}", {"path": str(path), "why": why})
    return path


Users = Annotated[dict, PlainValidator(_users)]
UsersFile = Annotated[Path | None, PlainValidator(_users_file)]
OptionalFile = Annotated[Path | None, PlainValidator(_optional_file)]
Host = Annotated[str, PlainValidator(_host)]
Port = Annotated[int, int_range(0, 65535)]
Patterns = Annotated[tuple, PlainValidator(_patterns)]
Period = Annotated[int, PlainValidator(positive_duration)]


@dataclass(frozen=True)
class ServerConfig:
    """What every server section has; a section's own keys in `options`."""

    key: str  # the section: "web", "opcua", "modbus_server"
    host: str
    port: int
    writable: tuple
    period_ns: int  # how often the server takes the engine's values
    options: dict = field(default_factory=dict)
    where: str = ""  # "[opcua] writable in plant.toml", for a refused write

    @property
    def public(self) -> bool:
        """True when the server listens beyond this machine."""
        return not _is_loopback(self.host)


def _is_loopback(host: str) -> bool:
    if host == "localhost":
        return True
    try:
        return ipaddress.ip_address(host).is_loopback
    except ValueError:
        return False


class _Web(Model):
    host: Host = Field(LOOPBACK, description='an address such as "127.0.0.1"')
    port: Port = Field(8080, description="a TCP port, 0 for any free one")
    writable: Patterns = Field(("*",), description='an array of patterns such as ["Main.*"]')
    period: Period = Field(250_000_000, description=f"a duration such as {DURATION_EXAMPLES}")
    #: the page may restart the tasks a fault stopped and trigger an online change
    control: bool = Field(True, description="true or false")


class _Opcua(Model):
    host: Host = Field(LOOPBACK, description='an address such as "127.0.0.1"')
    port: Port = Field(4840, description="a TCP port, 0 for any free one")
    writable: Patterns = Field((), description='an array of patterns such as ["Main.Setpoint"]')
    period: Period = Field(100_000_000, description=f"a duration such as {DURATION_EXAMPLES}")
    # the server's own keys (surfaces/opcua, docs/guide/surfaces.md "OPC UA")
    namespace: str = Field("urn:softplc", description='a namespace URI such as "urn:softplc"')
    max_variables: Annotated[int, int_range(1, 1_000_000)] = Field(10_000, description="an integer")
    anonymous: bool = Field(True, description="true or false")
    users: Users = Field(default_factory=dict, description='a table of user = "password or hash"')
    users_file: UsersFile = Field(None, description="the path of a TOML file with a [users] table")
    certificate: OptionalFile = Field(None, description="the path of the server certificate (DER or PEM)")
    private_key: OptionalFile = Field(None, description="the path of the certificate's private key (PEM)")


class _ModbusServer(Model):
    host: Host = Field(LOOPBACK, description='an address such as "127.0.0.1"')
    port: Port = Field(5020, description="a TCP port, 0 for any free one")
    writable: Patterns = Field(("%Q*", "%M*"), description='an array of patterns such as ["%QX*", "%MW*"]')
    period: Period = Field(100_000_000, description=f"a duration such as {DURATION_EXAMPLES}")
    unit: Annotated[int, int_range(0, 255)] = Field(0, description="a unit id 1..255, 0 for any")
    max_connections: Annotated[int, int_range(1, 1000)] = Field(32, description="an integer 1..1000")


class _ServerSection(Section):
    def build(self, model: Any, ctx: Relations) -> ServerConfig | None:
        if model is None:
            return None
        config = self.config(model)
        if config.public:
            ctx.warning(
                (self.key, "host"),
                f"listens on {config.host}: the PLC is reachable from the network (127.0.0.1 keeps it local)",
            )
        return config

    def config(self, model: Any) -> ServerConfig:
        """The ServerConfig of a validated table (the section's own keys in options)."""
        values = model.model_dump()
        common = {k: values.pop(k) for k in ("host", "port", "writable", "period")}
        return ServerConfig(
            key=self.key,
            host=common["host"],
            port=common["port"],
            writable=tuple(common["writable"]),
            period_ns=common["period"],
            options=values,
            where=f"[{self.key}] writable",
        )


class WebSection(_ServerSection):
    key = "web"
    model = _Web
    description = "a [web] table"


class OpcuaSection(_ServerSection):
    key = "opcua"
    model = _Opcua
    description = "an [opcua] table"

    def check(self, value: Any, ctx: Relations) -> None:
        if not isinstance(value, dict) or ("certificate" in value) == ("private_key" in value):
            return
        given, missing = ("certificate", "private_key") if "certificate" in value else ("private_key", "certificate")
        ctx.error(
            (self.key, given),
            f"{given} without {missing}: the certificate mode needs both (without them no encryption)",
        )


class ModbusServerSection(_ServerSection):
    key = "modbus_server"
    model = _ModbusServer
    description = "a [modbus_server] table"


SERVER_SECTIONS = (WebSection(), OpcuaSection(), ModbusServerSection())


def parse_listen(text: str) -> tuple:
    """`--web [HOST:]PORT` -> (host or None, port): "8080", "0.0.0.0:8080",
    "localhost:0", "[::1]:8080". ValueError says what is expected."""
    expected = f"expected [HOST:]PORT such as 8080 or 127.0.0.1:8080, not {text!r}"
    host, sep, port = text.strip().rpartition(":")
    if host.startswith("[") and host.endswith("]"):
        host = host[1:-1]
    if (sep and not host) or any(c.isspace() for c in host) or not port.isdigit() or int(port) > 65535:
        raise ValueError(expected)
    return (host or None), int(port)


def web_option(text: str, section: ServerConfig | None) -> ServerConfig:
    """The [web] server of `softplc run --web [HOST:]PORT`: the section's
    settings (or its defaults, without one) on that address."""
    host, port = parse_listen(text)
    if section is None:  # the [web] defaults
        section = WebSection().config(_Web.model_validate({}))
    return dataclasses.replace(section, host=host or section.host, port=port)
