"""The OPC UA server's certificate mode ([opcua] certificate and
private_key), seen by real asyncua clients on 127.0.0.1: certificates made
at test time, a client with its own certificate that reads and writes over
Basic256Sha256 with SignAndEncrypt, a client without one that gets nothing,
and the errors of a bad certificate file or a key that does not match."""

from __future__ import annotations

import ipaddress
import socket
import threading
from dataclasses import dataclass
from pathlib import Path

import pytest
from asyncua import Client, ua
from asyncua.crypto.cert_gen import (
    dump_private_key_as_pem,
    generate_private_key,
    generate_self_signed_app_certificate,
)
from asyncua.crypto.security_policies import SecurityPolicyBasic256Sha256
from cryptography import x509
from cryptography.hazmat.primitives import serialization
from cryptography.hazmat.primitives.serialization import Encoding
from cryptography.x509.oid import ExtendedKeyUsageOID

from softplc.runtime.surfaces.host import SurfaceError, Surfaces

from ...engine.conftest import make_engine, task
from .conftest import client, greater, opcua_config, run, until, value

SRC = """
PROGRAM Main
VAR
    n : INT;
    setpoint : REAL := 12.5;
    doubled : REAL;
END_VAR
n := n + 1;
doubled := setpoint * 2.0;
END_PROGRAM
"""
TASKS = [task("Main", 10, "Main")]
SERVER_URI = "urn:softplc:server"  # server.py: the namespace + ":server"
CLIENT_URI = "urn:softplc:test-client"
SIGN_AND_ENCRYPT = "Basic256Sha256,SignAndEncrypt"


@dataclass(frozen=True)
class Pki:
    """Files made for the tests: a server's certificate and key, a client's."""

    server_cert: Path  # DER
    server_key: Path  # PEM
    server_cert_pem: Path  # the same certificate as PEM, under a name that does not say so
    client_cert: Path
    client_key: Path
    locked_key: Path  # the server's key, protected by a password


def _certificate(key, name: str, uri: str, usage) -> x509.Certificate:
    alt_names = [
        x509.UniformResourceIdentifier(uri),
        x509.DNSName("localhost"),
        x509.DNSName(socket.gethostname()),  # asyncua's client looks for it (a warning otherwise)
        x509.IPAddress(ipaddress.ip_address("127.0.0.1")),
    ]
    return generate_self_signed_app_certificate(
        key, name, {"organizationName": "softplc tests"}, alt_names, [usage], days=2
    )


@pytest.fixture(scope="module")
def pki(tmp_path_factory) -> Pki:
    folder = tmp_path_factory.mktemp("pki")
    server_key, client_key = generate_private_key(), generate_private_key()
    server = _certificate(server_key, "softplc", SERVER_URI, ExtendedKeyUsageOID.SERVER_AUTH)
    client = _certificate(client_key, "test client", CLIENT_URI, ExtendedKeyUsageOID.CLIENT_AUTH)
    pki = Pki(
        *(folder / n for n in ("server.der", "server.pem", "server.crt", "client.der", "client.pem", "locked.pem"))
    )
    pki.server_cert.write_bytes(server.public_bytes(Encoding.DER))
    pki.server_cert_pem.write_bytes(server.public_bytes(Encoding.PEM))
    pki.client_cert.write_bytes(client.public_bytes(Encoding.DER))
    pki.server_key.write_bytes(dump_private_key_as_pem(server_key))
    pki.client_key.write_bytes(dump_private_key_as_pem(client_key))
    locked = serialization.BestAvailableEncryption(b"secret")
    pki.locked_key.write_bytes(server_key.private_bytes(Encoding.PEM, serialization.PrivateFormat.PKCS8, locked))
    return pki


async def secure_client(url: str, pki: Pki) -> Client:
    secure = client(url)
    secure.application_uri = CLIENT_URI  # as the client's certificate says
    await secure.set_security_string(f"{SIGN_AND_ENCRYPT},{pki.client_cert},{pki.client_key}")
    return secure


def test_a_client_with_a_certificate_reads_and_a_logged_in_one_writes(running, pki):
    plc = running(
        SRC,
        TASKS,
        writable=["Main.setpoint"],
        certificate=pki.server_cert,
        private_key=pki.server_key,
        users={"operator": "s3cret"},
    )
    setpoint = ua.DataValue(ua.Variant(20.0, ua.VariantType.Float))

    async def check() -> None:
        async with await secure_client(plc.url, pki) as reader:
            assert reader.security_policy.URI == SecurityPolicyBasic256Sha256.URI
            assert reader.security_policy.Mode == ua.MessageSecurityMode.SignAndEncrypt
            n = await until(lambda: value(reader, "Main.n"), "Main.n to count")
            await until(lambda: greater(value(reader, "Main.n"), n + 3), "Main.n to count on")
            with pytest.raises(ua.uaerrors.BadUserAccessDenied):  # anonymous: reads only
                await reader.get_node("ns=2;s=Main.setpoint").write_value(setpoint)
        operator = await secure_client(plc.url, pki)
        operator.set_user("operator")
        operator.set_password("s3cret")
        async with operator:
            await operator.get_node("ns=2;s=Main.setpoint").write_value(setpoint)
            assert plc.surfaces.access.place("Main.setpoint").read() == 20.0
            await until(lambda: _eq(value(operator, "Main.doubled"), 40.0), "the program to double the new setpoint")

    run(check())


async def _eq(read, expected):
    return (await read) == expected


def test_a_pem_certificate_under_any_name_is_taken(running, pki):
    plc = running(SRC, TASKS, certificate=pki.server_cert_pem, private_key=pki.server_key)

    async def check() -> None:
        async with await secure_client(plc.url, pki) as c:
            assert await value(c, "Main.setpoint") == 12.5

    run(check())


def careless(endpoints, security_mode, policy_uri):
    """Client.find_endpoint of a client that takes whatever the server describes."""
    token = ua.UserTokenPolicy(PolicyId="anonymous", TokenType=ua.UserTokenType.Anonymous)
    return ua.EndpointDescription(UserIdentityTokens=[token])


def test_only_the_encrypted_endpoint_is_offered_and_nothing_is_read_without_it(running, pki, monkeypatch):
    plc = running(SRC, TASKS, certificate=pki.server_cert, private_key=pki.server_key)

    async def check() -> None:
        endpoints = await client(plc.url).connect_and_get_server_endpoints()  # discovery: open
        assert [(e.SecurityPolicyUri, e.SecurityMode) for e in endpoints] == [
            (SecurityPolicyBasic256Sha256.URI, ua.MessageSecurityMode.SignAndEncrypt)
        ]
        assert endpoints[0].ServerCertificate == pki.server_cert.read_bytes()
        assert endpoints[0].Server.ApplicationUri == SERVER_URI  # as the certificate says
        with pytest.raises(ua.UaError, match="No matching endpoints"):  # what a plain asyncua client says
            await client(plc.url).connect()
        # a client that does not look at the endpoints opens an unencrypted session all the same:
        # the server refuses it
        monkeypatch.setattr(Client, "find_endpoint", staticmethod(careless))
        with pytest.raises(ua.uaerrors.BadSecurityModeInsufficient):
            await client(plc.url).connect()

    run(check())


def _bad(pki: Pki, case: str) -> tuple:
    """(certificate, private_key, what the error says) of a bad configuration."""
    folder = pki.server_cert.parent
    if case == "missing certificate":
        return folder / "nowhere.der", pki.server_key, r"certificate .*nowhere\.der: cannot be read"
    if case == "not a certificate":
        return pki.server_key, pki.server_key, r"certificate .*server\.pem: not an X\.509 certificate"
    if case == "key of another certificate":
        return pki.server_cert, pki.client_key, r"private_key .*client\.pem is not the key of certificate .*server\.der"
    if case == "key with a password":
        return pki.server_cert, pki.locked_key, r"private_key .*locked\.pem: the key is protected by a password"
    if case == "no key":
        return pki.server_cert, None, "certificate is given without private_key"
    raise AssertionError(case)


@pytest.mark.parametrize(
    "case", ["missing certificate", "not a certificate", "key of another certificate", "key with a password", "no key"]
)
def test_a_bad_certificate_or_key_is_an_error_at_start_naming_the_file(pki, case):
    certificate, key, says = _bad(pki, case)
    engine = make_engine(SRC, TASKS)
    surfaces = Surfaces(engine, {"opcua": opcua_config(certificate=certificate, private_key=key)})
    try:
        with pytest.raises(SurfaceError, match=r"^\[opcua\] CertificateError: " + says):
            surfaces.start()
        assert surfaces.process is None and not surfaces.handles
    finally:
        surfaces.stop()
        engine.stop()
    # the servers' process is gone, and the threads that served it
    assert not [t for t in threading.enumerate() if t.name.startswith("softplc-servers")]  # no thread left
