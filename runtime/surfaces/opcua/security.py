"""The certificate mode's files ([opcua] certificate and private_key),
read and checked before the server starts, so a wrong file is an error
naming it rather than a parse error from deep in a library, or a server
whose clients fail at their first handshake.

    certificate, key = load_credentials(Path("pki/server.der"), Path("pki/server.pem"))

Either file may be DER or PEM, whatever its name says (asyncua goes by the
suffix alone: a PEM certificate named ``server.crt`` would not load). The
key must be an RSA key without a password (Basic256Sha256 signs and
encrypts with RSA) and must be the certificate's.
"""

from __future__ import annotations

from pathlib import Path

from cryptography import x509
from cryptography.hazmat.primitives import serialization
from cryptography.hazmat.primitives.asymmetric import rsa


class CertificateError(ValueError):
    """A certificate or key that cannot be used: the message names the [opcua] key and the file
    (the PLC says "[opcua] CertificateError: certificate pki/server.der: ...")."""


def load_credentials(certificate: Path | None, private_key: Path | None) -> tuple:
    """(x509.Certificate, RSAPrivateKey) of the two files; CertificateError naming the one at fault."""
    if certificate is None or private_key is None:
        given, missing = ("certificate", "private_key") if private_key is None else ("private_key", "certificate")
        raise CertificateError(
            f"{given} is given without {missing}: the certificate mode needs both "
            "(without them the server would offer no encryption)"
        )
    cert = _certificate(certificate)
    key = _private_key(private_key)
    if _public(cert.public_key()) != _public(key.public_key()):
        raise CertificateError(f"private_key {private_key} is not the key of certificate {certificate}")
    return cert, key


def _public(key) -> bytes:
    return key.public_bytes(serialization.Encoding.DER, serialization.PublicFormat.SubjectPublicKeyInfo)


def _read(name: str, path: Path) -> bytes:
    try:
        return Path(path).read_bytes()
    except OSError as exc:
        raise CertificateError(f"{name} {path}: cannot be read: {exc.strerror or exc}") from None


def _is_pem(data: bytes) -> bool:
    return data.lstrip().startswith(b"-----BEGIN")


def _certificate(path: Path) -> x509.Certificate:
    data = _read("certificate", path)
    try:
        return x509.load_pem_x509_certificate(data) if _is_pem(data) else x509.load_der_x509_certificate(data)
    except ValueError:
        raise CertificateError(f"certificate {path}: not an X.509 certificate (DER or PEM)") from None


def _private_key(path: Path) -> rsa.RSAPrivateKey:
    data = _read("private_key", path)
    load = serialization.load_pem_private_key if _is_pem(data) else serialization.load_der_private_key
    try:
        key = load(data, password=None)
    except TypeError:  # protected by a password
        raise CertificateError(
            f"private_key {path}: the key is protected by a password; give it without one "
            "(openssl pkey -in KEY -out server.pem) and keep the file readable only by the PLC's user"
        ) from None
    except ValueError:
        raise CertificateError(f"private_key {path}: not a private key (PEM or DER)") from None
    if not isinstance(key, rsa.RSAPrivateKey):
        raise CertificateError(f"private_key {path}: not an RSA key, which Basic256Sha256 needs")
    return key
