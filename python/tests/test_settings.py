"""Settings as dicts: defaults out, overrides in, the same values back."""
import json

import pytest

import penumbra
from conftest import run_cli


def test_defaults_are_the_cli_defaults(cli):
    expected = json.loads(run_cli("settings", "--json").stdout)
    flat = {}

    def flatten(node, prefix):
        for key, value in node.items():
            if isinstance(value, dict):
                flatten(value, prefix + key + ".")
            else:
                flat[prefix + key] = value

    flatten(expected, "")
    assert penumbra.default_settings() == flat


def test_defaults_round_trip():
    defaults = penumbra.default_settings()
    assert penumbra.validate_settings(defaults) == defaults
    assert penumbra.validate_settings({}) == defaults
    assert penumbra.validate_settings(None) == defaults


def test_changed_values_round_trip():
    changed = {
        "shadows.directional.filter": "PCF7x7",
        "shadows.directional.cascadeCount": 2,
        "shadows.directional.cascadeBlend": "soft",
        "shadows.maxDistance": 42.5,
        "render.exposure": 1.25,
    }
    result = penumbra.validate_settings(changed)
    for key, value in changed.items():
        assert result[key] == value
    assert penumbra.validate_settings(result) == result
    untouched = {k: v for k, v in result.items() if k not in changed}
    defaults = penumbra.default_settings()
    assert untouched == {k: v for k, v in defaults.items() if k not in changed}


def test_nested_dicts_equal_dotted_keys():
    nested = {"shadows": {"directional": {"filter": "PCF5x5"}, "maxDistance": 80}}
    dotted = {"shadows.directional.filter": "PCF5x5", "shadows.maxDistance": 80}
    assert penumbra.validate_settings(nested) == penumbra.validate_settings(dotted)


def test_ratios_take_a_list_and_numpy_values():
    import numpy as np
    keys = [k for k, v in penumbra.default_settings().items() if isinstance(v, list)]
    assert keys, "no ratios key"
    result = penumbra.validate_settings({keys[0]: np.array([0.1, 0.3, 0.6]), "render.exposure": np.float32(2.0)})
    assert result[keys[0]] == pytest.approx([0.1, 0.3, 0.6])
    assert result["render.exposure"] == 2.0


def test_reference_table_describes_every_key():
    table = penumbra.settings_reference()
    defaults = penumbra.default_settings()
    assert table.keys() == defaults.keys()
    for key, entry in table.items():
        assert entry["default"] == defaults[key]
        assert entry["description"] and entry["allowed"]
