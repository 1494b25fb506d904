"""Each vocabulary is listed once (core.vocabulary) and everything else is derived from it:
every shape class names a distinct kernel kind, the model's CSG operations and sampling
patterns are the vocabulary's, and the A4 language's CSG names map onto all of them."""

from core import vocabulary
from core.cs488.graph import A4_OPERATIONS
from core.model import RenderSettings, shapes
from core.model.settings import PIXEL_SAMPLINGS, SHADOW_SAMPLINGS


def test_every_shape_class_has_its_own_kernel_kind():
    classes = [*shapes.ANALYTIC_SHAPES, shapes.Mesh, shapes.Csg]
    kinds = [cls.kernel_kind for cls in classes]
    listed = {v for k, v in vars(vocabulary).items() if k.startswith("SHAPE_")}
    assert sorted(kinds) == sorted(listed) and len(set(kinds)) == len(kinds)


def test_the_models_names_are_the_vocabularys():
    assert set(A4_OPERATIONS.values()) == set(vocabulary.CSG_OPERATIONS)
    assert tuple(vocabulary.PIXEL_PATTERNS) == PIXEL_SAMPLINGS
    assert tuple(vocabulary.SHADOW_PATTERNS) == SHADOW_SAMPLINGS
    defaults = RenderSettings()
    assert defaults.pixel_sampling in PIXEL_SAMPLINGS
    assert defaults.shadow_sampling in SHADOW_SAMPLINGS
