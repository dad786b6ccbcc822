"""protobuf_bytes.py - protobuf's wire format written by hand, for models no ONNX library would write: a singular
message given twice (make_onnx_seeds.py, tests/faults/faults_round6_test.sh)."""


def varint(value):
    out = bytearray()
    while value >= 0x80:
        out.append((value & 0x7f) | 0x80)
        value >>= 7
    out.append(value)
    return bytes(out)


def field(number, payload):
    """A length-delimited field: key, length, payload."""
    return varint(number << 3 | 2) + varint(len(payload)) + payload


def number(field_number, value):
    """A varint field."""
    return varint(field_number << 3) + varint(value)
