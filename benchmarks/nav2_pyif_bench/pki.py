"""Throwaway certificates for the TLS tests and benchmark: a certificate authority and the
certificates it signs (EC P-256, PKCS#8 keys, as the deployment guide makes them with openssl).
Written into a directory the caller owns (a test's tmp_path); none is ever committed.

Needs the ``cryptography`` package (the ``dev`` extra).
"""

from __future__ import annotations

import datetime
import ipaddress
from dataclasses import dataclass
from pathlib import Path
from typing import Any

try:
    from cryptography import x509
    from cryptography.hazmat.primitives import hashes, serialization
    from cryptography.hazmat.primitives.asymmetric import ec
    from cryptography.x509.oid import ExtendedKeyUsageOID, NameOID
except ImportError as exc:  # pragma: no cover - the dev extra has it
    raise ImportError(
        "nav2_pyif_bench.pki needs the 'cryptography' package: pip install cryptography "
        "(it is in nav2_pyif's dev extra)"
    ) from exc

#: Every certificate is valid from an hour ago (clock skew) for this long.
VALIDITY = datetime.timedelta(days=2)


@dataclass(frozen=True)
class Identity:
    """A certificate and its private key, as PEM files: Zenoh's ``*_certificate`` and
    ``*_private_key`` settings."""

    common_name: str
    certificate: Path
    private_key: Path


def _write_key(path: Path, key: ec.EllipticCurvePrivateKey) -> None:
    path.write_bytes(
        key.private_bytes(
            serialization.Encoding.PEM,
            serialization.PrivateFormat.PKCS8,
            serialization.NoEncryption(),
        )
    )
    path.chmod(0o600)


def _name(common_name: str) -> x509.Name:
    return x509.Name([x509.NameAttribute(NameOID.COMMON_NAME, common_name)])


def _alternative_name(host: str) -> Any:
    try:
        return x509.IPAddress(ipaddress.ip_address(host))
    except ValueError:
        return x509.DNSName(host)


class CertificateAuthority:
    """A self-signed CA in ``directory`` (``<name>.pem``; its key stays in memory) that
    issues leaf certificates for Zenoh's TLS links."""

    def __init__(self, directory: Path, name: str = "ca") -> None:
        self.directory = directory
        directory.mkdir(parents=True, exist_ok=True)
        self._key = ec.generate_private_key(ec.SECP256R1())
        now = datetime.datetime.now(datetime.timezone.utc)
        self._subject = _name(f"nav2_pyif test CA {name}")
        cert = (
            self._builder(self._subject, self._key.public_key(), now)
            .add_extension(x509.BasicConstraints(ca=True, path_length=0), critical=True)
            .add_extension(_usage(cert_sign=True), critical=True)
            .sign(self._key, hashes.SHA256())
        )
        self.certificate = directory / f"{name}.pem"
        self.certificate.write_bytes(cert.public_bytes(serialization.Encoding.PEM))

    def _builder(self, subject: x509.Name, public_key: Any, now: datetime.datetime) -> Any:
        return (
            x509.CertificateBuilder()
            .subject_name(subject)
            .issuer_name(self._subject)
            .public_key(public_key)
            .serial_number(x509.random_serial_number())
            .not_valid_before(now - datetime.timedelta(hours=1))
            .not_valid_after(now + VALIDITY)
        )

    def issue(self, common_name: str, hosts: tuple[str, ...] = ()) -> Identity:
        """A certificate with CN ``common_name`` (what Zenoh's access control matches as
        ``cert_common_names``) for both TLS roles, listening (``hosts``: the DNS names and
        IP addresses it is reached at, checked by ``verify_name_on_connect``) and connecting
        (a client certificate for mutual TLS)."""
        key = ec.generate_private_key(ec.SECP256R1())
        now = datetime.datetime.now(datetime.timezone.utc)
        names = [_alternative_name(h) for h in (hosts or (common_name,))]
        cert = (
            self._builder(_name(common_name), key.public_key(), now)
            .add_extension(x509.BasicConstraints(ca=False, path_length=None), critical=True)
            .add_extension(_usage(cert_sign=False), critical=True)
            .add_extension(
                x509.ExtendedKeyUsage(
                    [ExtendedKeyUsageOID.SERVER_AUTH, ExtendedKeyUsageOID.CLIENT_AUTH]
                ),
                critical=False,
            )
            .add_extension(x509.SubjectAlternativeName(names), critical=False)
            .sign(self._key, hashes.SHA256())
        )
        identity = Identity(
            common_name,
            self.directory / f"{common_name}.pem",
            self.directory / f"{common_name}-key.pem",
        )
        identity.certificate.write_bytes(cert.public_bytes(serialization.Encoding.PEM))
        _write_key(identity.private_key, key)
        return identity


def _usage(*, cert_sign: bool) -> x509.KeyUsage:
    return x509.KeyUsage(
        digital_signature=not cert_sign,
        content_commitment=False,
        key_encipherment=False,
        data_encipherment=False,
        key_agreement=False,
        key_cert_sign=cert_sign,
        crl_sign=cert_sign,
        encipher_only=False,
        decipher_only=False,
    )
