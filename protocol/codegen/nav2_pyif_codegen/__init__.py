"""The protocol's code generators, for developing nav2_pyif (not installed with it): from the
one description of the protocol (``nav2_pyif_protocol.schema`` and ``.constants``), the C++
message structs, codec and error tables and PROTOCOL.md's field tables (``generate``), and the
shared test vectors both codecs must reproduce (``vectors``, the ``nav2-pyif-vectors``
command)."""
