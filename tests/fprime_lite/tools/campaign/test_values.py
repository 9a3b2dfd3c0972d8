"""Campaign values written as scenario settings read back as the same values."""
import yaml

from fprime_lite.tools.campaign.values import yaml_text


def test_floats_read_back_as_floats_through_yaml():
    """CAMP-VAL-001: every float, in lists and mappings too, comes back from YAML 1.1 as the same
    float — JSON's ``1e-05`` would come back as the string '1e-05' (the noise-study bug)."""
    for value in (1e-05, 4.0e-4, 1e22, -2.5e-300, 0.1, 3.0, 12345678.9):
        assert yaml.safe_load(yaml_text(value)) == value
    nested = {"a": [1e-05, 2, True, "x"], "b": {"c": 1e-20}}
    assert yaml.safe_load(yaml_text(nested)) == nested
    assert yaml.safe_load(yaml_text([0.0, -0.0, 1e100])) == [0.0, -0.0, 1e100]
