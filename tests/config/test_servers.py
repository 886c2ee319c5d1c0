"""The keys every server section has (runtime/config/servers.py): the host
it listens on, checked as a host before any socket sees it; and the OPC UA
users file, read when the configuration is."""

from __future__ import annotations

import pytest

from .support import PLC, error, load

HOST = 'expected a host name or address to listen on, such as "127.0.0.1" or "0.0.0.0"'


@pytest.mark.parametrize(
    "host", ["127.0.0.1", "0.0.0.0", "::1", "[::1]", "localhost", "plc-7.plant.example", "a" * 63 + ".example."]
)
@pytest.mark.parametrize("section", ["web", "opcua", "modbus_server"])
def test_a_host_is_an_address_or_a_host_name(tmp_path, section, host):
    assert load(tmp_path, PLC + f'[{section}]\nhost = "{host}"\n').sections[section].host == host


@pytest.mark.parametrize(
    ("host", "shown"),
    [
        ("h" * 1_000_000, f"'{'h' * 60}…' (1000000 characters)"),  # was echoed whole, then an idna UnicodeError
        ("a" * 64 + ".example", f"'{'a' * 64}.example'"),
        (".".join(["a"] * 130), f"'{'a.' * 30}…' (259 characters)"),
        ("plc 7", "'plc 7'"),
        ("-plc", "'-plc'"),
        ("plc..local", "'plc..local'"),
        ("", "''"),
    ],
    ids=["1 MB", "a label of 64", "259 characters", "a space", "a leading hyphen", "an empty label", "empty"],
)
def test_what_no_name_service_takes_is_refused(tmp_path, host, shown):
    assert error(tmp_path, PLC + f'[web]\nhost = "{host}"\n') == ("web.host", f"{HOST} (got {shown})")


def test_a_users_file_that_is_no_list_of_users_is_the_keys_error(tmp_path):
    """A users file not in UTF-8 was '[opcua] UnicodeDecodeError', from the
    server's process, naming neither the file nor the key."""
    (tmp_path / "users.toml").write_bytes(b"\xff\xfe[users]\n")
    assert error(tmp_path, PLC + "[opcua]\nusers_file = 'users.toml'\n") == (
        "opcua.users_file",
        f"{tmp_path / 'users.toml'}: not UTF-8 text (byte 0); a TOML file is UTF-8",
    )
    (tmp_path / "users.toml").write_text("[users\n")
    key, message = error(tmp_path, PLC + "[opcua]\nusers_file = 'users.toml'\n")
    assert key == "opcua.users_file" and message.startswith(f"{tmp_path / 'users.toml'}: invalid TOML: ")
    (tmp_path / "users.toml").write_text("[users]\noperator = 7\n")
    assert error(tmp_path, PLC + "[opcua]\nusers_file = 'users.toml'\n") == (
        "opcua.users_file",
        f'{tmp_path / "users.toml"}: expected a [users] table of name = "password or hash"',
    )
