"""The input contract of a compiled core: what each port of its top means (being written)."""

__all__ = ["input_contract", "contract_lines"]


def input_contract(config, spec, method, *, n_scale=1):
    """The contract of the shader ``config`` compiled for ``method`` from the scene ``spec``."""
    raise NotImplementedError


def contract_lines(contract):
    """The header's "Contract" paragraphs of ``contract``."""
    raise NotImplementedError
