"""The [opcua] keys of the server itself: users, a users file, the
certificate's files, the cap on published variables; each bad one named."""

from __future__ import annotations

from ...config.support import PLC, error, load


def test_the_opcua_keys_are_read_with_paths_from_the_config_directory(tmp_path):
    (tmp_path / "users.toml").write_text('[users]\noperator = "secret"\n')
    (tmp_path / "server.der").write_bytes(b"")
    (tmp_path / "server.pem").write_bytes(b"")
    cfg = load(
        tmp_path,
        PLC + "[opcua]\nusers = { viewer = 'x' }\nusers_file = 'users.toml'\nanonymous = false\n"
        "certificate = 'server.der'\nprivate_key = 'server.pem'\nmax_variables = 500\n",
    )
    options = cfg.sections["opcua"].options
    assert options["users"] == {"viewer": "x"} and options["users_file"] == tmp_path / "users.toml"
    assert options["certificate"] == tmp_path / "server.der" and options["private_key"] == tmp_path / "server.pem"
    assert options["anonymous"] is False and options["max_variables"] == 500
    assert options["namespace"] == "urn:softplc"


def test_a_bad_opcua_key_names_the_key(tmp_path):
    assert error(tmp_path, PLC + "[opcua]\nusers = { viewer = 3 }\n")[0] == "opcua.users"
    (tmp_path / "server.pem").write_bytes(b"")
    assert error(tmp_path, PLC + "[opcua]\ncertificate = 'nowhere.der'\nprivate_key = 'server.pem'\n")[0] == (
        "opcua.certificate"
    )
    assert error(tmp_path, PLC + "[opcua]\nmax_variables = 0\n") == (
        "opcua.max_variables",
        "expected an integer from 1 to 1000000 (got 0)",
    )


def test_a_certificate_without_its_key_is_refused_when_the_config_is_read(tmp_path):
    (tmp_path / "server.der").write_bytes(b"")
    (tmp_path / "server.pem").write_bytes(b"")
    assert error(tmp_path, PLC + "[opcua]\ncertificate = 'server.der'\n") == (
        "opcua.certificate",
        "certificate without private_key: the certificate mode needs both (without them no encryption)",
    )
    assert error(tmp_path, PLC + "[opcua]\nprivate_key = 'server.pem'\n")[0] == "opcua.private_key"
