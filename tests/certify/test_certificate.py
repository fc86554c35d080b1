"""The certificate's record: what the manifest keeps reads back as the same certificate."""

from phongfx.certify.certificate import Certificate, integer_bound, meets


def test_a_certificate_reads_back_from_its_dict():
    cert = Certificate(True, 1.4984, "interval", {"rounding": 0.9, "output": 0.5, "regions": [{"name": "a"}]}, "", 8.7)
    data = {**cert.as_dict(), "refined": "until it met the requirement (early)"}  # a search result's extra key
    back = Certificate.from_dict(data)
    assert back == cert and back.parts is not cert.parts
    unbounded = Certificate.from_dict({"certified": False, "bound_levels": None, "method": "interval"})
    assert unbounded.why == "" and unbounded.parts == {} and not meets(unbounded.bound_levels, 1)
    assert integer_bound(cert.bound_levels) == 1 and meets(cert.bound_levels, 1)
