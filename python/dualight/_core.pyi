"""
dualight's compiled core; use the `dualight` package instead of this module.
"""
from __future__ import annotations
import collections.abc
import numpy
import numpy.typing
import typing
__all__: list[str] = ['BLOCK_SPP', 'BdptOptions', 'Bsdf', 'BsdfKind', 'ChainPart', 'ChainStartUp', 'DirectSolver', 'Emitter', 'Film', 'FormFactorOptions', 'FormFactors', 'GaussSeidelSolver', 'Guide', 'HierarchicalOptions', 'HierarchicalSolver', 'JacobiSolver', 'LaneIsa', 'LightTracerOptions', 'MAX_DIRECT_PATCHES', 'MAX_GUIDE_RECORDS', 'MisHeuristic', 'MltOptions', 'PathTracerOptions', 'PinholeCamera', 'PssmltOptions', 'RadiositySystem', 'RefinementOracle', 'SamplerType', 'Scene', 'SouthwellSolver', 'Strategies', 'Texture', 'TransportMode', 'cast_random_rays', 'compute_form_factors', 'direct_irradiance', 'finish_chains', 'fresnel_dielectric', 'guide_from_records', 'point_polygon_form_factor', 'read_image', 'render_bdpt', 'render_light', 'render_mlt', 'render_path', 'render_pssmlt', 'run_chains', 'start_chains', 'trace_camera_hits', 'train_importance_guide', 'train_radiance_guide', 'with_guide_start', 'write_image']
class Scene:
    """
    Immutable triangle scene committed to Embree (built by dualight.Scene).
    """
    def __init__(self, positions: typing.Annotated[numpy.typing.ArrayLike, numpy.float32], triangles: typing.Annotated[numpy.typing.ArrayLike, numpy.uint32], material_of: typing.Annotated[numpy.typing.ArrayLike, numpy.uint32], reflectance: typing.Annotated[numpy.typing.ArrayLike, numpy.float32], emission: typing.Annotated[numpy.typing.ArrayLike, numpy.float32], *, kind: typing.Annotated[numpy.typing.ArrayLike, numpy.uint32] | None = None, ior: typing.Annotated[numpy.typing.ArrayLike, numpy.float32] | None = None, bsdfs: collections.abc.Sequence[...] | None = None, normals: typing.Annotated[numpy.typing.ArrayLike, numpy.float32] | None = None, uvs: typing.Annotated[numpy.typing.ArrayLike, numpy.float32] | None = None, textures: collections.abc.Sequence[collections.abc.Sequence[tuple[str, ...]]] | None = None, emitters: collections.abc.Sequence[...] | None = None, emission_textures: collections.abc.Sequence[... | None] | None = None, robust_intersections: bool = True) -> None:
        """
        Triangles with one material per row of reflectance and emission. The BSDFs: bsdfs (one dualight._core.Bsdf per material), or kind (BsdfKind values, default lambertian) and ior (a dielectric's interior IOR) as optional per-material arrays with reflectance the diffuse albedo or the mirror's reflectance. normals: optional shading normals, one row per position; a triangle is smooth-shaded when its three vertices have non-zero normals. uvs: optional surface coordinates, one row per position (NaN for meshes without). textures: per material, a list of (BSDF parameter name, Texture). emitters: point and spot lights (dualight._core.Emitter). emission_textures: per material, the Texture of its emitted radiance (an area light whose radiance varies over its surface) or None. robust_intersections: Embree's robust mode (no ray slips through where triangles meet; off, 8-19 % more samples per second but leaky, is Mitsuba 3's default).
        """
    def encloses(self, point: typing.Annotated[collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], "FixedSize(3)"]) -> bool:
        """
        Whether point lies strictly inside the scene's convex enclosure (False if none).
        """
    def intersect(self, origins: typing.Annotated[numpy.typing.ArrayLike, numpy.float32], directions: typing.Annotated[numpy.typing.ArrayLike, numpy.float32]) -> tuple[numpy.typing.NDArray[numpy.float32], numpy.typing.NDArray[numpy.int64]]:
        """
        Closest hits of rays: (t, triangle index or -1); directions need not be normalised.
        """
    @property
    def bounds(self) -> tuple[typing.Annotated[list[float], "FixedSize(3)"], typing.Annotated[list[float], "FixedSize(3)"]]:
        ...
    @property
    def emitter_count(self) -> int:
        ...
    @property
    def features(self) -> dict:
        """
        What the scene holds, computed once at construction (see scene_features.h).
        """
    @property
    def has_hittable_emitter(self) -> bool:
        """
        Whether a path can hit an emitter (an area light or an environment); false when every emitter is a point, spot or directional light.
        """
    @property
    def robust_intersections(self) -> bool:
        ...
    @property
    def triangle_count(self) -> int:
        ...
class PinholeCamera:
    """
    Pinhole camera (built by dualight.Camera).
    """
    def __init__(self, origin: typing.Annotated[collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], "FixedSize(3)"], target: typing.Annotated[collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], "FixedSize(3)"], up: typing.Annotated[collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], "FixedSize(3)"], fov: typing.SupportsFloat | typing.SupportsIndex, width: typing.SupportsInt | typing.SupportsIndex, height: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def generate_ray(self, x: typing.SupportsFloat | typing.SupportsIndex, y: typing.SupportsFloat | typing.SupportsIndex) -> tuple[typing.Annotated[list[float], "FixedSize(3)"], typing.Annotated[list[float], "FixedSize(3)"]]:
        """
        Ray (origin, unit direction) through film position (x, y) in pixels.
        """
    @property
    def height(self) -> int:
        ...
    @property
    def width(self) -> int:
        ...
class BsdfKind:
    """
    Kinds of BSDF; the values index the arrays of Scene(kind=...).
    
    Members:
    
      lambertian
    
      mirror
    
      dielectric
    
      conductor
    
      rough_conductor
    
      thin_dielectric
    
      rough_dielectric
    
      plastic
    
      rough_plastic
    """
    __members__: typing.ClassVar[dict[str, BsdfKind]]
    conductor: typing.ClassVar[BsdfKind]
    dielectric: typing.ClassVar[BsdfKind]
    lambertian: typing.ClassVar[BsdfKind]
    mirror: typing.ClassVar[BsdfKind]
    plastic: typing.ClassVar[BsdfKind]
    rough_conductor: typing.ClassVar[BsdfKind]
    rough_dielectric: typing.ClassVar[BsdfKind]
    rough_plastic: typing.ClassVar[BsdfKind]
    thin_dielectric: typing.ClassVar[BsdfKind]
    @typing.overload
    def __eq__(self, other: BsdfKind) -> bool:
        ...
    @typing.overload
    def __eq__(self, other: typing.Any) -> bool:
        ...
    def __getstate__(self) -> int:
        ...
    def __hash__(self) -> int:
        ...
    def __index__(self) -> int:
        ...
    def __init__(self, value: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __int__(self) -> int:
        ...
    @typing.overload
    def __ne__(self, other: BsdfKind) -> bool:
        ...
    @typing.overload
    def __ne__(self, other: typing.Any) -> bool:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, state: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __str__(self) -> str:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def value(self) -> int:
        ...
class TransportMode:
    """
    Which quantity a path carries (radiance from lights, importance from the camera).
    
    Members:
    
      radiance
    
      importance
    """
    __members__: typing.ClassVar[dict[str, TransportMode]]
    importance: typing.ClassVar[TransportMode]
    radiance: typing.ClassVar[TransportMode]
    @typing.overload
    def __eq__(self, other: TransportMode) -> bool:
        ...
    @typing.overload
    def __eq__(self, other: typing.Any) -> bool:
        ...
    def __getstate__(self) -> int:
        ...
    def __hash__(self) -> int:
        ...
    def __index__(self) -> int:
        ...
    def __init__(self, value: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __int__(self) -> int:
        ...
    @typing.overload
    def __ne__(self, other: TransportMode) -> bool:
        ...
    @typing.overload
    def __ne__(self, other: typing.Any) -> bool:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, state: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __str__(self) -> str:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def value(self) -> int:
        ...
class Bsdf:
    """
    One BSDF in its local frame (z = geometric normal, the exterior side for a dielectric); vectorised for tests. Directions point away from the surface.
    """
    @staticmethod
    def conductor(*, eta: typing.Annotated[collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], "FixedSize(3)"] = [0.0, 0.0, 0.0], k: typing.Annotated[collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], "FixedSize(3)"] = [1.0, 1.0, 1.0], specular_reflectance: typing.Annotated[collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], "FixedSize(3)"] = [1.0, 1.0, 1.0], two_sided: bool = False) -> Bsdf:
        """
        Mitsuba's `conductor`: a smooth metal with complex IOR eta + i k (eta 0, k 1: a perfect mirror).
        """
    @staticmethod
    def plastic(*, diffuse_reflectance: typing.Annotated[collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], "FixedSize(3)"] = [0.5, 0.5, 0.5], specular_reflectance: typing.Annotated[collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], "FixedSize(3)"] = [1.0, 1.0, 1.0], ior: typing.SupportsFloat | typing.SupportsIndex = 1.4900000095367432, nonlinear: bool = False, two_sided: bool = False) -> Bsdf:
        """
        Mitsuba's `plastic` (diffuse base under a smooth coat).
        """
    @staticmethod
    def rough_conductor(*, distribution: str = 'beckmann', alpha_u: typing.SupportsFloat | typing.SupportsIndex = 0.10000000149011612, alpha_v: typing.SupportsFloat | typing.SupportsIndex = 0.10000000149011612, eta: typing.Annotated[collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], "FixedSize(3)"] = [0.0, 0.0, 0.0], k: typing.Annotated[collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], "FixedSize(3)"] = [1.0, 1.0, 1.0], specular_reflectance: typing.Annotated[collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], "FixedSize(3)"] = [1.0, 1.0, 1.0], two_sided: bool = False) -> Bsdf:
        """
        Mitsuba's `roughconductor` (microfacet metal).
        """
    @staticmethod
    def rough_dielectric(*, distribution: str = 'beckmann', alpha_u: typing.SupportsFloat | typing.SupportsIndex = 0.10000000149011612, alpha_v: typing.SupportsFloat | typing.SupportsIndex = 0.10000000149011612, ior: typing.SupportsFloat | typing.SupportsIndex = 1.5046000480651855) -> Bsdf:
        """
        Mitsuba's `roughdielectric` (frosted glass; ior = interior / exterior).
        """
    @staticmethod
    def rough_plastic(*, distribution: str = 'beckmann', alpha: typing.SupportsFloat | typing.SupportsIndex = 0.10000000149011612, diffuse_reflectance: typing.Annotated[collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], "FixedSize(3)"] = [0.5, 0.5, 0.5], specular_reflectance: typing.Annotated[collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], "FixedSize(3)"] = [1.0, 1.0, 1.0], ior: typing.SupportsFloat | typing.SupportsIndex = 1.4900000095367432, nonlinear: bool = False, two_sided: bool = False) -> Bsdf:
        """
        Mitsuba's `roughplastic` (diffuse base under a rough coat; isotropic).
        """
    @staticmethod
    def thin_dielectric(*, ior: typing.SupportsFloat | typing.SupportsIndex = 1.5046000480651855) -> Bsdf:
        """
        Mitsuba's `thindielectric` (a pane: reflection or straight through).
        """
    def __init__(self, kind: BsdfKind, *, reflectance: typing.Annotated[collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], "FixedSize(3)"] = [1.0, 1.0, 1.0], ior: typing.SupportsFloat | typing.SupportsIndex = 1.5) -> None:
        ...
    def eval_f(self, wo: typing.Annotated[numpy.typing.ArrayLike, numpy.float32], wi: typing.Annotated[numpy.typing.ArrayLike, numpy.float32], mode: TransportMode = TransportMode.radiance) -> numpy.typing.NDArray[numpy.float32]:
        """
        The BSDF value f(wo, wi) (N, 3); 0 for delta BSDFs.
        """
    def pdf_w(self, wo: typing.Annotated[numpy.typing.ArrayLike, numpy.float32], wi: typing.Annotated[numpy.typing.ArrayLike, numpy.float32], mode: TransportMode = TransportMode.radiance) -> numpy.typing.NDArray[numpy.float32]:
        """
        Solid-angle density (N,) of sample() producing wi given wo; 0 for delta BSDFs.
        """
    def sample(self, wo: typing.Annotated[numpy.typing.ArrayLike, numpy.float32], u: typing.Annotated[numpy.typing.ArrayLike, numpy.float32], mode: TransportMode = TransportMode.radiance) -> dict:
        """
        Sample wi for each row of wo (N, 3) with random numbers u (N, 2): a dict of wi (N, 3), weight = f |cos wi| / pdf (N, 3), pdf_w (N,) (the lobe's probability when delta), delta (N,) and valid (N,), False where sampling failed (the other fields are then 0).
        """
    @property
    def flags(self) -> list[str]:
        """
        What the BSDF is, as it reports itself: a subset of diffuse, glossy, specular (Dirac lobes), reflection, transmission.
        """
    @property
    def is_delta(self) -> bool:
        ...
    @property
    def is_diffuse_reflector(self) -> bool:
        """
        Only diffuse reflection: what radiosity can solve.
        """
    @property
    def kind(self) -> BsdfKind:
        ...
class Texture:
    """
    A bitmap or checkerboard texture (Mitsuba 3's semantics).
    """
    @staticmethod
    def bitmap(texels: typing.Annotated[numpy.typing.ArrayLike, numpy.float32], *, wrap_mode: str = 'repeat', filter_type: str = 'bilinear', to_uv: typing.Annotated[collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], "FixedSize(6)"] = [1.0, 0.0, 0.0, 0.0, 1.0, 0.0]) -> Texture:
        """
        Linear texels (height, width, 1 or 3), row 0 at v = 0.
        """
    @staticmethod
    def checkerboard(color0: typing.Annotated[collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], "FixedSize(3)"], color1: typing.Annotated[collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], "FixedSize(3)"], *, to_uv: typing.Annotated[collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], "FixedSize(6)"] = [1.0, 0.0, 0.0, 0.0, 1.0, 0.0]) -> Texture:
        ...
    def eval(self, uv: typing.Annotated[numpy.typing.ArrayLike, numpy.float32]) -> numpy.typing.NDArray[numpy.float32]:
        """
        RGB at each row (u, v) of an (N, 2) array: (N, 3).
        """
    def eval_scalar(self, uv: typing.Annotated[numpy.typing.ArrayLike, numpy.float32]) -> numpy.typing.NDArray[numpy.float32]:
        """
        The value a roughness takes at each row (u, v): (N,).
        """
    @property
    def mean(self) -> typing.Annotated[list[float], "FixedSize(3)"]:
        ...
class Emitter:
    """
    An emitter without a surface (built by dualight.PointLight, SpotLight, DirectionalLight, ConstantEnvironment, EnvironmentMap).
    """
    @staticmethod
    def constant(radiance: typing.Annotated[collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], "FixedSize(3)"]) -> Emitter:
        """
        Constant environment: radiance from every direction.
        """
    @staticmethod
    def directional(direction: typing.Annotated[collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], "FixedSize(3)"], irradiance: typing.Annotated[collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], "FixedSize(3)"]) -> Emitter:
        """
        Directional light: irradiance in W/m^2 per channel, travelling along direction.
        """
    @staticmethod
    def envmap(rgb: typing.Annotated[numpy.typing.ArrayLike, numpy.float32], scale: typing.SupportsFloat | typing.SupportsIndex, to_world: typing.Annotated[collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], "FixedSize(9)"]) -> Emitter:
        """
        Latitude-longitude environment (Mitsuba 3's envmap conventions): rgb (height, width, 3) linear radiance, scale, to_world a 3 x 3 rotation (row-major).
        """
    @staticmethod
    def point(position: typing.Annotated[collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], "FixedSize(3)"], intensity: typing.Annotated[collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], "FixedSize(3)"]) -> Emitter:
        """
        Isotropic point light: intensity in W/sr per channel.
        """
    @staticmethod
    def spot(position: typing.Annotated[collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], "FixedSize(3)"], direction: typing.Annotated[collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], "FixedSize(3)"], intensity: typing.Annotated[collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], "FixedSize(3)"], cutoff_angle: typing.SupportsFloat | typing.SupportsIndex, beam_width: typing.SupportsFloat | typing.SupportsIndex) -> Emitter:
        """
        Spot light (Mitsuba 3's spot): angles in degrees, intensity on the axis in W/sr.
        """
    @property
    def power(self) -> float:
        """
        Flux / pi (the weight of the scene's light choice; for emitters at infinity, over a unit bounding sphere until a scene holds them).
        """
class Film:
    """
    A film's totals, to merge the tasks of a split render: add each task's accumulators (render_*(..., accumulators=True)) in block order, then read mean() and variance(), computed as a single render computes them.
    """
    def __init__(self, width: typing.SupportsInt | typing.SupportsIndex, height: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def accumulators(self) -> dict:
        ...
    def add_accumulators(self, accumulators: dict) -> None:
        ...
    def counts(self) -> numpy.typing.NDArray[numpy.uint32]:
        ...
    def mean(self) -> numpy.typing.NDArray[numpy.float32]:
        ...
    def variance(self) -> numpy.typing.NDArray[numpy.float32]:
        ...
    @property
    def light_paths(self) -> int:
        ...
class SamplerType:
    """
    Members:
    
      independent
    
      sobol
    """
    __members__: typing.ClassVar[dict[str, SamplerType]]
    independent: typing.ClassVar[SamplerType]
    sobol: typing.ClassVar[SamplerType]
    @typing.overload
    def __eq__(self, other: SamplerType) -> bool:
        ...
    @typing.overload
    def __eq__(self, other: typing.Any) -> bool:
        ...
    def __getstate__(self) -> int:
        ...
    def __hash__(self) -> int:
        ...
    def __index__(self) -> int:
        ...
    def __init__(self, value: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __int__(self) -> int:
        ...
    @typing.overload
    def __ne__(self, other: SamplerType) -> bool:
        ...
    @typing.overload
    def __ne__(self, other: typing.Any) -> bool:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, state: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __str__(self) -> str:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def value(self) -> int:
        ...
class Strategies:
    """
    Members:
    
      mis
    
      bsdf
    
      light
    """
    __members__: typing.ClassVar[dict[str, Strategies]]
    bsdf: typing.ClassVar[Strategies]
    light: typing.ClassVar[Strategies]
    mis: typing.ClassVar[Strategies]
    @typing.overload
    def __eq__(self, other: Strategies) -> bool:
        ...
    @typing.overload
    def __eq__(self, other: typing.Any) -> bool:
        ...
    def __getstate__(self) -> int:
        ...
    def __hash__(self) -> int:
        ...
    def __index__(self) -> int:
        ...
    def __init__(self, value: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __int__(self) -> int:
        ...
    @typing.overload
    def __ne__(self, other: Strategies) -> bool:
        ...
    @typing.overload
    def __ne__(self, other: typing.Any) -> bool:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, state: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __str__(self) -> str:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def value(self) -> int:
        ...
class LaneIsa:
    """
    Members:
    
      auto
    
      off
    
      sse2
    
      avx2
    
      avx512
    """
    __members__: typing.ClassVar[dict[str, LaneIsa]]
    auto: typing.ClassVar[LaneIsa]
    avx2: typing.ClassVar[LaneIsa]
    avx512: typing.ClassVar[LaneIsa]
    off: typing.ClassVar[LaneIsa]
    sse2: typing.ClassVar[LaneIsa]
    @typing.overload
    def __eq__(self, other: LaneIsa) -> bool:
        ...
    @typing.overload
    def __eq__(self, other: typing.Any) -> bool:
        ...
    def __getstate__(self) -> int:
        ...
    def __hash__(self) -> int:
        ...
    def __index__(self) -> int:
        ...
    def __init__(self, value: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __int__(self) -> int:
        ...
    @typing.overload
    def __ne__(self, other: LaneIsa) -> bool:
        ...
    @typing.overload
    def __ne__(self, other: typing.Any) -> bool:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, state: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __str__(self) -> str:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def value(self) -> int:
        ...
class PathTracerOptions:
    """
    Options of the path tracer.
    """
    _fields: typing.ClassVar[tuple] = ('spp', 'max_depth', 'rr_depth', 'seed', 'threads', 'time_limit', 'skip_unneeded', 'sampler', 'first_sample', 'strategies', 'lanes', 'guiding', 'guide_training', 'guide_keep_iterations', 'guide_trial', 'guide_learn_bsdf_fraction', 'guide_bsdf_fraction', 'guide_spatial_threshold', 'guide_adjoint_roulette', 'guide_rho', 'guide_max_records')
    def __init__(self, *, spp: int = 64, max_depth: int = -1, rr_depth: int = 5, seed: int = 0, threads: int = 0, time_limit: float = 0.0, skip_unneeded: bool = True, sampler: SamplerType | str = ..., first_sample: int = 0, strategies: Strategies | str = ..., lanes: LaneIsa | str = ..., guiding: bool = False, guide_training: float = 0.25, guide_keep_iterations: int = 2, guide_trial: bool = True, guide_learn_bsdf_fraction: bool = True, guide_bsdf_fraction: float = 0.5, guide_spatial_threshold: int = 1000, guide_adjoint_roulette: bool = True, guide_rho: float = 0.01, guide_max_records: int = 8388608) -> None:
        """
        Options of the path tracer. Keywords only: an option left out keeps its default above (the C++ PathTracerOptions{}); an unknown one is a TypeError, a bad value a ValueError naming it.
        
        spp: Samples per pixel; 0 = until time_limit.
        max_depth: Longest path in segments, as in Mitsuba (1: emitters seen directly); -1 = unbounded.
        rr_depth: Russian roulette from this path vertex on.
        seed: The image depends on the seed only, not on the threads.
        threads: Worker threads; 0 = all cores.
        time_limit: Seconds of wall time; 0 = none.
        skip_unneeded: Skip work the scene makes pointless; False does it all.
        sampler: Where the random numbers come from (core/sampler.h).
        first_sample: First sample index rendered (one task of a split render; see Film).
        strategies: mis: light and BSDF sampling combined by MIS; bsdf or light: that strategy alone (the other only where it alone can find the light).
        lanes: auto: a tile row's paths at a time in SIMD lanes where the CPU runs AVX-512 or AVX2 and the render is unguided (materials other than untextured diffuse, mirror or smooth glass, and emitters other than untextured area emitters, lane by lane); off: one path at a time; sse2, avx2 or avx512: that build. The image is the same, bit for bit.
        guiding: Train a guide first, then sample directions from it (guiding/).
        guide_training: Share of the budget (spp, or time_limit) spent training, in iterations of 1, 2, 4, ... spp; with spp the image still has spp samples per pixel.
        guide_keep_iterations: The image keeps the samples of this many last training iterations (0: none; BDPT with strategy_images: none), as unbiased as its own; the stats' kept_spp counts them.
        guide_trial: Under a time limit, render before the last training iteration (or after training) a guided and an unguided pass of half the last iteration's spp each (at least 32; kept in the image), and the image with the more efficient of the two (guided when the passes disagree beyond their variances; unguided stops the training).
        guide_learn_bsdf_fraction: Learn each spatial leaf's probability of sampling the BSDF (of 0.1, ..., 1, at least guide_bsdf_fraction: the least second moment over its records); else guide_bsdf_fraction everywhere.
        guide_bsdf_fraction: Probability of sampling the BSDF instead of the guide (one-sample MIS); the least one when learnt.
        guide_spatial_threshold: Records a spatial leaf may hold at 1 spp before it is split (times sqrt(spp)).
        guide_adjoint_roulette: 'path': adjoint-driven Russian roulette and splitting (Vorba and Krivanek 2016) in the final render and the training iterations after the first, from the guide's reflected-radiance estimates and the previous iteration's image.
        guide_rho: A directional node holding more than this share of its leaf's value is split.
        guide_max_records: Records one training iteration may keep (24 bytes each); training stops before more.
        """
    def __repr__(self) -> str:
        ...
    @property
    def first_sample(self) -> int:
        """
        First sample index rendered (one task of a split render; see Film).
        """
    @property
    def guide_adjoint_roulette(self) -> bool:
        """
        'path': adjoint-driven Russian roulette and splitting (Vorba and Krivanek 2016) in the final render and the training iterations after the first, from the guide's reflected-radiance estimates and the previous iteration's image.
        """
    @property
    def guide_bsdf_fraction(self) -> float:
        """
        Probability of sampling the BSDF instead of the guide (one-sample MIS); the least one when learnt.
        """
    @property
    def guide_keep_iterations(self) -> int:
        """
        The image keeps the samples of this many last training iterations (0: none; BDPT with strategy_images: none), as unbiased as its own; the stats' kept_spp counts them.
        """
    @property
    def guide_learn_bsdf_fraction(self) -> bool:
        """
        Learn each spatial leaf's probability of sampling the BSDF (of 0.1, ..., 1, at least guide_bsdf_fraction: the least second moment over its records); else guide_bsdf_fraction everywhere.
        """
    @property
    def guide_max_records(self) -> int:
        """
        Records one training iteration may keep (24 bytes each); training stops before more.
        """
    @property
    def guide_rho(self) -> float:
        """
        A directional node holding more than this share of its leaf's value is split.
        """
    @property
    def guide_spatial_threshold(self) -> int:
        """
        Records a spatial leaf may hold at 1 spp before it is split (times sqrt(spp)).
        """
    @property
    def guide_training(self) -> float:
        """
        Share of the budget (spp, or time_limit) spent training, in iterations of 1, 2, 4, ... spp; with spp the image still has spp samples per pixel.
        """
    @property
    def guide_trial(self) -> bool:
        """
        Under a time limit, render before the last training iteration (or after training) a guided and an unguided pass of half the last iteration's spp each (at least 32; kept in the image), and the image with the more efficient of the two (guided when the passes disagree beyond their variances; unguided stops the training).
        """
    @property
    def guiding(self) -> bool:
        """
        Train a guide first, then sample directions from it (guiding/).
        """
    @property
    def lanes(self) -> LaneIsa:
        """
        auto: a tile row's paths at a time in SIMD lanes where the CPU runs AVX-512 or AVX2 and the render is unguided (materials other than untextured diffuse, mirror or smooth glass, and emitters other than untextured area emitters, lane by lane); off: one path at a time; sse2, avx2 or avx512: that build. The image is the same, bit for bit.
        """
    @property
    def max_depth(self) -> int:
        """
        Longest path in segments, as in Mitsuba (1: emitters seen directly); -1 = unbounded.
        """
    @property
    def rr_depth(self) -> int:
        """
        Russian roulette from this path vertex on.
        """
    @property
    def sampler(self) -> SamplerType:
        """
        Where the random numbers come from (core/sampler.h).
        """
    @property
    def seed(self) -> int:
        """
        The image depends on the seed only, not on the threads.
        """
    @property
    def skip_unneeded(self) -> bool:
        """
        Skip work the scene makes pointless; False does it all.
        """
    @property
    def spp(self) -> int:
        """
        Samples per pixel; 0 = until time_limit.
        """
    @property
    def strategies(self) -> Strategies:
        """
        mis: light and BSDF sampling combined by MIS; bsdf or light: that strategy alone (the other only where it alone can find the light).
        """
    @property
    def threads(self) -> int:
        """
        Worker threads; 0 = all cores.
        """
    @property
    def time_limit(self) -> float:
        """
        Seconds of wall time; 0 = none.
        """
class MisHeuristic:
    """
    Members:
    
      power
    
      balance
    """
    __members__: typing.ClassVar[dict[str, MisHeuristic]]
    balance: typing.ClassVar[MisHeuristic]
    power: typing.ClassVar[MisHeuristic]
    @typing.overload
    def __eq__(self, other: MisHeuristic) -> bool:
        ...
    @typing.overload
    def __eq__(self, other: typing.Any) -> bool:
        ...
    def __getstate__(self) -> int:
        ...
    def __hash__(self) -> int:
        ...
    def __index__(self) -> int:
        ...
    def __init__(self, value: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __int__(self) -> int:
        ...
    @typing.overload
    def __ne__(self, other: MisHeuristic) -> bool:
        ...
    @typing.overload
    def __ne__(self, other: typing.Any) -> bool:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, state: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __str__(self) -> str:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def value(self) -> int:
        ...
class LightTracerOptions:
    """
    Options of the light tracer.
    """
    _fields: typing.ClassVar[tuple] = ('spp', 'max_depth', 'rr_depth', 'seed', 'threads', 'time_limit', 'skip_unneeded', 'sampler', 'first_sample', 'guiding', 'guide_training', 'guide_keep_iterations', 'guide_trial', 'guide_learn_bsdf_fraction', 'guide_bsdf_fraction', 'guide_spatial_threshold', 'guide_adjoint_roulette', 'guide_rho', 'guide_max_records')
    def __init__(self, *, spp: int = 64, max_depth: int = -1, rr_depth: int = 5, seed: int = 0, threads: int = 0, time_limit: float = 0.0, skip_unneeded: bool = True, sampler: SamplerType | str = ..., first_sample: int = 0, guiding: bool = False, guide_training: float = 0.25, guide_keep_iterations: int = 2, guide_trial: bool = True, guide_learn_bsdf_fraction: bool = True, guide_bsdf_fraction: float = 0.5, guide_spatial_threshold: int = 1000, guide_adjoint_roulette: bool = True, guide_rho: float = 0.01, guide_max_records: int = 8388608) -> None:
        """
        Options of the light tracer. Keywords only: an option left out keeps its default above (the C++ LightTracerOptions{}); an unknown one is a TypeError, a bad value a ValueError naming it.
        
        spp: Particles per pixel (spp x pixels particles in all); 0 = until time_limit.
        max_depth: Longest path in segments, as in Mitsuba (1: emitters seen directly); -1 = unbounded.
        rr_depth: Russian roulette from this path vertex on.
        seed: The image depends on the seed only, not on the threads.
        threads: Worker threads; 0 = all cores.
        time_limit: Seconds of wall time; 0 = none.
        skip_unneeded: Skip work the scene makes pointless; False does it all.
        sampler: Where the random numbers come from (core/sampler.h).
        first_sample: First sample index rendered (one task of a split render; see Film).
        guiding: Train a guide first, then sample directions from it (guiding/).
        guide_training: Share of the budget (spp, or time_limit) spent training, in iterations of 1, 2, 4, ... spp; with spp the image still has spp samples per pixel.
        guide_keep_iterations: The image keeps the samples of this many last training iterations (0: none; BDPT with strategy_images: none), as unbiased as its own; the stats' kept_spp counts them.
        guide_trial: Under a time limit, render before the last training iteration (or after training) a guided and an unguided pass of half the last iteration's spp each (at least 32; kept in the image), and the image with the more efficient of the two (guided when the passes disagree beyond their variances; unguided stops the training).
        guide_learn_bsdf_fraction: Learn each spatial leaf's probability of sampling the BSDF (of 0.1, ..., 1, at least guide_bsdf_fraction: the least second moment over its records); else guide_bsdf_fraction everywhere.
        guide_bsdf_fraction: Probability of sampling the BSDF instead of the guide (one-sample MIS); the least one when learnt.
        guide_spatial_threshold: Records a spatial leaf may hold at 1 spp before it is split (times sqrt(spp)).
        guide_adjoint_roulette: 'path': adjoint-driven Russian roulette and splitting (Vorba and Krivanek 2016) in the final render and the training iterations after the first, from the guide's reflected-radiance estimates and the previous iteration's image.
        guide_rho: A directional node holding more than this share of its leaf's value is split.
        guide_max_records: Records one training iteration may keep (24 bytes each); training stops before more.
        """
    def __repr__(self) -> str:
        ...
    @property
    def first_sample(self) -> int:
        """
        First sample index rendered (one task of a split render; see Film).
        """
    @property
    def guide_adjoint_roulette(self) -> bool:
        """
        'path': adjoint-driven Russian roulette and splitting (Vorba and Krivanek 2016) in the final render and the training iterations after the first, from the guide's reflected-radiance estimates and the previous iteration's image.
        """
    @property
    def guide_bsdf_fraction(self) -> float:
        """
        Probability of sampling the BSDF instead of the guide (one-sample MIS); the least one when learnt.
        """
    @property
    def guide_keep_iterations(self) -> int:
        """
        The image keeps the samples of this many last training iterations (0: none; BDPT with strategy_images: none), as unbiased as its own; the stats' kept_spp counts them.
        """
    @property
    def guide_learn_bsdf_fraction(self) -> bool:
        """
        Learn each spatial leaf's probability of sampling the BSDF (of 0.1, ..., 1, at least guide_bsdf_fraction: the least second moment over its records); else guide_bsdf_fraction everywhere.
        """
    @property
    def guide_max_records(self) -> int:
        """
        Records one training iteration may keep (24 bytes each); training stops before more.
        """
    @property
    def guide_rho(self) -> float:
        """
        A directional node holding more than this share of its leaf's value is split.
        """
    @property
    def guide_spatial_threshold(self) -> int:
        """
        Records a spatial leaf may hold at 1 spp before it is split (times sqrt(spp)).
        """
    @property
    def guide_training(self) -> float:
        """
        Share of the budget (spp, or time_limit) spent training, in iterations of 1, 2, 4, ... spp; with spp the image still has spp samples per pixel.
        """
    @property
    def guide_trial(self) -> bool:
        """
        Under a time limit, render before the last training iteration (or after training) a guided and an unguided pass of half the last iteration's spp each (at least 32; kept in the image), and the image with the more efficient of the two (guided when the passes disagree beyond their variances; unguided stops the training).
        """
    @property
    def guiding(self) -> bool:
        """
        Train a guide first, then sample directions from it (guiding/).
        """
    @property
    def max_depth(self) -> int:
        """
        Longest path in segments, as in Mitsuba (1: emitters seen directly); -1 = unbounded.
        """
    @property
    def rr_depth(self) -> int:
        """
        Russian roulette from this path vertex on.
        """
    @property
    def sampler(self) -> SamplerType:
        """
        Where the random numbers come from (core/sampler.h).
        """
    @property
    def seed(self) -> int:
        """
        The image depends on the seed only, not on the threads.
        """
    @property
    def skip_unneeded(self) -> bool:
        """
        Skip work the scene makes pointless; False does it all.
        """
    @property
    def spp(self) -> int:
        """
        Particles per pixel (spp x pixels particles in all); 0 = until time_limit.
        """
    @property
    def threads(self) -> int:
        """
        Worker threads; 0 = all cores.
        """
    @property
    def time_limit(self) -> float:
        """
        Seconds of wall time; 0 = none.
        """
class BdptOptions:
    """
    Options of bidirectional path tracing.
    """
    _fields: typing.ClassVar[tuple] = ('spp', 'max_depth', 'rr_depth', 'seed', 'threads', 'time_limit', 'skip_unneeded', 'sampler', 'first_sample', 'heuristic', 'strategies', 'strategy_images', 'light_pool', 'guiding', 'guide_training', 'guide_keep_iterations', 'guide_trial', 'guide_learn_bsdf_fraction', 'guide_bsdf_fraction', 'guide_spatial_threshold', 'guide_adjoint_roulette', 'guide_rho', 'guide_max_records')
    def __init__(self, *, spp: int = 64, max_depth: int = -1, rr_depth: int = 2, seed: int = 0, threads: int = 0, time_limit: float = 0.0, skip_unneeded: bool = True, sampler: SamplerType | str = ..., first_sample: int = 0, heuristic: MisHeuristic | str = ..., strategies: Strategies | str = ..., strategy_images: bool = False, light_pool: int = 16, guiding: bool = False, guide_training: float = 0.25, guide_keep_iterations: int = 2, guide_trial: bool = True, guide_learn_bsdf_fraction: bool = True, guide_bsdf_fraction: float = 0.5, guide_spatial_threshold: int = 1000, guide_adjoint_roulette: bool = True, guide_rho: float = 0.01, guide_max_records: int = 8388608) -> None:
        """
        Options of bidirectional path tracing. Keywords only: an option left out keeps its default above (the C++ BdptOptions{}); an unknown one is a TypeError, a bad value a ValueError naming it.
        
        spp: Samples per pixel; 0 = until time_limit.
        max_depth: Longest path in segments, as in Mitsuba (1: emitters seen directly); -1 = unbounded.
        rr_depth: Russian roulette from this path vertex on.
        seed: The image depends on the seed only, not on the threads.
        threads: Worker threads; 0 = all cores.
        time_limit: Seconds of wall time; 0 = none.
        skip_unneeded: Skip work the scene makes pointless; False does it all.
        sampler: Where the random numbers come from (core/sampler.h).
        first_sample: First sample index rendered (one task of a split render; see Film).
        heuristic: How the strategies' samples are weighted (MIS).
        strategies: mis: every strategy by MIS; bsdf: the fewest light vertices (s = 0) that can sample each path; light: s = 1 first, then s = 0, 2, 3, ...
        strategy_images: Also an image per strategy (s, t), MIS-weighted; they sum to the image (needs a bounded max_depth).
        light_pool: Each connection (s >= 2, t >= 2) takes the light subpath of another pixel of its group of light_pool pixels (same tile row, same sample index), a different one per strategy; 1: the sample's own (classic BDPT). Guided BDPT uses 1.
        guiding: Train a guide first, then sample directions from it (guiding/).
        guide_training: Share of the budget (spp, or time_limit) spent training, in iterations of 1, 2, 4, ... spp; with spp the image still has spp samples per pixel.
        guide_keep_iterations: The image keeps the samples of this many last training iterations (0: none; BDPT with strategy_images: none), as unbiased as its own; the stats' kept_spp counts them.
        guide_trial: Under a time limit, render before the last training iteration (or after training) a guided and an unguided pass of half the last iteration's spp each (at least 32; kept in the image), and the image with the more efficient of the two (guided when the passes disagree beyond their variances; unguided stops the training).
        guide_learn_bsdf_fraction: Learn each spatial leaf's probability of sampling the BSDF (of 0.1, ..., 1, at least guide_bsdf_fraction: the least second moment over its records); else guide_bsdf_fraction everywhere.
        guide_bsdf_fraction: Probability of sampling the BSDF instead of the guide (one-sample MIS); the least one when learnt.
        guide_spatial_threshold: Records a spatial leaf may hold at 1 spp before it is split (times sqrt(spp)).
        guide_adjoint_roulette: 'path': adjoint-driven Russian roulette and splitting (Vorba and Krivanek 2016) in the final render and the training iterations after the first, from the guide's reflected-radiance estimates and the previous iteration's image.
        guide_rho: A directional node holding more than this share of its leaf's value is split.
        guide_max_records: Records one training iteration may keep (24 bytes each); training stops before more.
        """
    def __repr__(self) -> str:
        ...
    @property
    def first_sample(self) -> int:
        """
        First sample index rendered (one task of a split render; see Film).
        """
    @property
    def guide_adjoint_roulette(self) -> bool:
        """
        'path': adjoint-driven Russian roulette and splitting (Vorba and Krivanek 2016) in the final render and the training iterations after the first, from the guide's reflected-radiance estimates and the previous iteration's image.
        """
    @property
    def guide_bsdf_fraction(self) -> float:
        """
        Probability of sampling the BSDF instead of the guide (one-sample MIS); the least one when learnt.
        """
    @property
    def guide_keep_iterations(self) -> int:
        """
        The image keeps the samples of this many last training iterations (0: none; BDPT with strategy_images: none), as unbiased as its own; the stats' kept_spp counts them.
        """
    @property
    def guide_learn_bsdf_fraction(self) -> bool:
        """
        Learn each spatial leaf's probability of sampling the BSDF (of 0.1, ..., 1, at least guide_bsdf_fraction: the least second moment over its records); else guide_bsdf_fraction everywhere.
        """
    @property
    def guide_max_records(self) -> int:
        """
        Records one training iteration may keep (24 bytes each); training stops before more.
        """
    @property
    def guide_rho(self) -> float:
        """
        A directional node holding more than this share of its leaf's value is split.
        """
    @property
    def guide_spatial_threshold(self) -> int:
        """
        Records a spatial leaf may hold at 1 spp before it is split (times sqrt(spp)).
        """
    @property
    def guide_training(self) -> float:
        """
        Share of the budget (spp, or time_limit) spent training, in iterations of 1, 2, 4, ... spp; with spp the image still has spp samples per pixel.
        """
    @property
    def guide_trial(self) -> bool:
        """
        Under a time limit, render before the last training iteration (or after training) a guided and an unguided pass of half the last iteration's spp each (at least 32; kept in the image), and the image with the more efficient of the two (guided when the passes disagree beyond their variances; unguided stops the training).
        """
    @property
    def guiding(self) -> bool:
        """
        Train a guide first, then sample directions from it (guiding/).
        """
    @property
    def heuristic(self) -> MisHeuristic:
        """
        How the strategies' samples are weighted (MIS).
        """
    @property
    def light_pool(self) -> int:
        """
        Each connection (s >= 2, t >= 2) takes the light subpath of another pixel of its group of light_pool pixels (same tile row, same sample index), a different one per strategy; 1: the sample's own (classic BDPT). Guided BDPT uses 1.
        """
    @property
    def max_depth(self) -> int:
        """
        Longest path in segments, as in Mitsuba (1: emitters seen directly); -1 = unbounded.
        """
    @property
    def rr_depth(self) -> int:
        """
        Russian roulette from this path vertex on.
        """
    @property
    def sampler(self) -> SamplerType:
        """
        Where the random numbers come from (core/sampler.h).
        """
    @property
    def seed(self) -> int:
        """
        The image depends on the seed only, not on the threads.
        """
    @property
    def skip_unneeded(self) -> bool:
        """
        Skip work the scene makes pointless; False does it all.
        """
    @property
    def spp(self) -> int:
        """
        Samples per pixel; 0 = until time_limit.
        """
    @property
    def strategies(self) -> Strategies:
        """
        mis: every strategy by MIS; bsdf: the fewest light vertices (s = 0) that can sample each path; light: s = 1 first, then s = 0, 2, 3, ...
        """
    @property
    def strategy_images(self) -> bool:
        """
        Also an image per strategy (s, t), MIS-weighted; they sum to the image (needs a bounded max_depth).
        """
    @property
    def threads(self) -> int:
        """
        Worker threads; 0 = all cores.
        """
    @property
    def time_limit(self) -> float:
        """
        Seconds of wall time; 0 = none.
        """
class PssmltOptions:
    """
    Options of primary-sample-space MLT (and multiplexed MLT).
    """
    _fields: typing.ClassVar[tuple] = ('mutations_per_pixel', 'max_depth', 'rr_depth', 'seed', 'threads', 'time_limit', 'skip_unneeded', 'bootstrap', 'chains', 'sigma', 'large_step_probability', 'large_step_mis', 'heuristic', 'direct_spp', 'multiplexed')
    def __init__(self, *, mutations_per_pixel: int = 64, max_depth: int = -1, rr_depth: int = 5, seed: int = 0, threads: int = 0, time_limit: float = 0.0, skip_unneeded: bool = True, bootstrap: int = 100000, chains: int = 256, sigma: float = 0.01, large_step_probability: float = 0.3, large_step_mis: bool = True, heuristic: MisHeuristic | str = ..., direct_spp: int = 128, multiplexed: bool = False) -> None:
        """
        Options of primary-sample-space MLT (and multiplexed MLT). Keywords only: an option left out keeps its default above (the C++ PssmltOptions{}); an unknown one is a TypeError, a bad value a ValueError naming it.
        
        mutations_per_pixel: Mutations per pixel; 0 = until time_limit.
        max_depth: Longest path in segments, as in Mitsuba (1: emitters seen directly); -1 = unbounded.
        rr_depth: Russian roulette from this path vertex on.
        seed: The image depends on the seed only, not on the threads.
        threads: Worker threads; 0 = all cores.
        time_limit: Seconds of wall time; 0 = none.
        skip_unneeded: Skip work the scene makes pointless; False does it all.
        bootstrap: Independent samples that estimate b (per path length when multiplexed) and start the chains.
        chains: Markov chains.
        sigma: Deviation of a small step, per random number.
        large_step_probability: Probability that a mutation is a large step (fresh numbers).
        large_step_mis: Kelemen's MIS: large steps' proposals also count as independent samples.
        heuristic: BDPT's MIS heuristic (bootstrap, chains, direct light).
        direct_spp: BDPT samples per pixel of the paths of 1 and 2 segments, left out of the chains; 0 keeps them in.
        multiplexed: Multiplexed MLT: chains per path length, each sample one BDPT strategy (needs a bounded max_depth).
        """
    def __repr__(self) -> str:
        ...
    @property
    def bootstrap(self) -> int:
        """
        Independent samples that estimate b (per path length when multiplexed) and start the chains.
        """
    @property
    def chains(self) -> int:
        """
        Markov chains.
        """
    @property
    def direct_spp(self) -> int:
        """
        BDPT samples per pixel of the paths of 1 and 2 segments, left out of the chains; 0 keeps them in.
        """
    @property
    def heuristic(self) -> MisHeuristic:
        """
        BDPT's MIS heuristic (bootstrap, chains, direct light).
        """
    @property
    def large_step_mis(self) -> bool:
        """
        Kelemen's MIS: large steps' proposals also count as independent samples.
        """
    @property
    def large_step_probability(self) -> float:
        """
        Probability that a mutation is a large step (fresh numbers).
        """
    @property
    def max_depth(self) -> int:
        """
        Longest path in segments, as in Mitsuba (1: emitters seen directly); -1 = unbounded.
        """
    @property
    def multiplexed(self) -> bool:
        """
        Multiplexed MLT: chains per path length, each sample one BDPT strategy (needs a bounded max_depth).
        """
    @property
    def mutations_per_pixel(self) -> int:
        """
        Mutations per pixel; 0 = until time_limit.
        """
    @property
    def rr_depth(self) -> int:
        """
        Russian roulette from this path vertex on.
        """
    @property
    def seed(self) -> int:
        """
        The image depends on the seed only, not on the threads.
        """
    @property
    def sigma(self) -> float:
        """
        Deviation of a small step, per random number.
        """
    @property
    def skip_unneeded(self) -> bool:
        """
        Skip work the scene makes pointless; False does it all.
        """
    @property
    def threads(self) -> int:
        """
        Worker threads; 0 = all cores.
        """
    @property
    def time_limit(self) -> float:
        """
        Seconds of wall time; 0 = none.
        """
class MltOptions:
    """
    Options of path-space Metropolis light transport.
    """
    _fields: typing.ClassVar[tuple] = ('mutations_per_pixel', 'max_depth', 'rr_depth', 'seed', 'threads', 'time_limit', 'skip_unneeded', 'bootstrap', 'chains', 'heuristic', 'direct_spp', 'bidirectional', 'lens_subpath', 'lens_perturbation', 'caustic_perturbation', 'multi_chain_perturbation', 'lens_radius_min', 'lens_radius_max', 'angle_min', 'angle_max', 'importance')
    def __init__(self, *, mutations_per_pixel: int = 64, max_depth: int = -1, rr_depth: int = 5, seed: int = 0, threads: int = 0, time_limit: float = 0.0, skip_unneeded: bool = True, bootstrap: int = 100000, chains: int = 256, heuristic: MisHeuristic | str = ..., direct_spp: int = 128, bidirectional: float = 1.0, lens_subpath: float = 0.25, lens_perturbation: float = 1.0, caustic_perturbation: float = 1.0, multi_chain_perturbation: float = 1.0, lens_radius_min: float = 0.1, lens_radius_max: float = 0.0, angle_min: float = 1e-04, angle_max: float = 0.1, importance: str = 'luminance') -> None:
        """
        Options of path-space Metropolis light transport. Keywords only: an option left out keeps its default above (the C++ MltOptions{}); an unknown one is a TypeError, a bad value a ValueError naming it.
        
        mutations_per_pixel: Mutations per pixel; 0 = until time_limit.
        max_depth: Longest path in segments, as in Mitsuba (1: emitters seen directly); -1 = unbounded.
        rr_depth: Russian roulette from this path vertex on.
        seed: The image depends on the seed only, not on the threads.
        threads: Worker threads; 0 = all cores.
        time_limit: Seconds of wall time; 0 = none.
        skip_unneeded: Skip work the scene makes pointless; False does it all.
        bootstrap: BDPT samples that estimate b and start the chains.
        chains: Markov chains.
        heuristic: MIS heuristic of the bootstrap samples and the direct light.
        direct_spp: BDPT samples per pixel of the paths of 1 and 2 segments, left out of the chains; 0 keeps them in.
        bidirectional: Selection weight of the bidirectional mutation.
        lens_subpath: Selection weight; 0 disables it.
        lens_perturbation: Selection weight; 0 disables it.
        caustic_perturbation: Selection weight; 0 disables it.
        multi_chain_perturbation: Selection weight; 0 disables it.
        lens_radius_min: Smallest film offset of the lens and multi-chain perturbations, in pixels.
        lens_radius_max: Largest film offset, in pixels; 0 = a tenth of the film's width.
        angle_min: Smallest angular offset of the caustic and multi-chain perturbations, in radians.
        angle_max: Largest angular offset, in radians.
        importance: The chains' target: image luminance (Veach), or luminance over the square root of a smoothed pilot estimate of the pixel's brightness (mlt_importance.h).
        """
    def __repr__(self) -> str:
        ...
    @property
    def angle_max(self) -> float:
        """
        Largest angular offset, in radians.
        """
    @property
    def angle_min(self) -> float:
        """
        Smallest angular offset of the caustic and multi-chain perturbations, in radians.
        """
    @property
    def bidirectional(self) -> float:
        """
        Selection weight of the bidirectional mutation.
        """
    @property
    def bootstrap(self) -> int:
        """
        BDPT samples that estimate b and start the chains.
        """
    @property
    def caustic_perturbation(self) -> float:
        """
        Selection weight; 0 disables it.
        """
    @property
    def chains(self) -> int:
        """
        Markov chains.
        """
    @property
    def direct_spp(self) -> int:
        """
        BDPT samples per pixel of the paths of 1 and 2 segments, left out of the chains; 0 keeps them in.
        """
    @property
    def heuristic(self) -> MisHeuristic:
        """
        MIS heuristic of the bootstrap samples and the direct light.
        """
    @property
    def importance(self) -> str:
        """
        The chains' target: image luminance (Veach), or luminance over the square root of a smoothed pilot estimate of the pixel's brightness (mlt_importance.h).
        """
    @property
    def lens_perturbation(self) -> float:
        """
        Selection weight; 0 disables it.
        """
    @property
    def lens_radius_max(self) -> float:
        """
        Largest film offset, in pixels; 0 = a tenth of the film's width.
        """
    @property
    def lens_radius_min(self) -> float:
        """
        Smallest film offset of the lens and multi-chain perturbations, in pixels.
        """
    @property
    def lens_subpath(self) -> float:
        """
        Selection weight; 0 disables it.
        """
    @property
    def max_depth(self) -> int:
        """
        Longest path in segments, as in Mitsuba (1: emitters seen directly); -1 = unbounded.
        """
    @property
    def multi_chain_perturbation(self) -> float:
        """
        Selection weight; 0 disables it.
        """
    @property
    def mutations_per_pixel(self) -> int:
        """
        Mutations per pixel; 0 = until time_limit.
        """
    @property
    def rr_depth(self) -> int:
        """
        Russian roulette from this path vertex on.
        """
    @property
    def seed(self) -> int:
        """
        The image depends on the seed only, not on the threads.
        """
    @property
    def skip_unneeded(self) -> bool:
        """
        Skip work the scene makes pointless; False does it all.
        """
    @property
    def threads(self) -> int:
        """
        Worker threads; 0 = all cores.
        """
    @property
    def time_limit(self) -> float:
        """
        Seconds of wall time; 0 = none.
        """
class ChainStartUp:
    """
    What every chain of an MLT render needs: direct light, bootstrap, b, chain starts (picklable).
    """
    def __getstate__(self) -> bytes:
        ...
    def __setstate__(self, arg0: bytes) -> None:
        ...
    def for_chains(self, first_chain: typing.SupportsInt | typing.SupportsIndex, chain_count: typing.SupportsInt | typing.SupportsIndex) -> ChainStartUp:
        """
        A copy holding only what chains [first_chain, first_chain + chain_count) need (smaller to send).
        """
    @property
    def b(self) -> float:
        """
        The bootstrap's normalisation (sum over populations).
        """
    @property
    def cancelled(self) -> bool:
        ...
    @property
    def chains(self) -> int:
        """
        Chains in all populations.
        """
    @property
    def populations(self) -> int:
        ...
    @property
    def seconds(self) -> float:
        ...
class ChainPart:
    """
    What a range of chains produced (picklable).
    """
    def __getstate__(self) -> bytes:
        ...
    def __setstate__(self, arg0: bytes) -> None:
        ...
    @property
    def chains(self) -> int:
        ...
    @property
    def first_chain(self) -> int:
        ...
    @property
    def interrupted(self) -> bool:
        ...
    @property
    def mutations(self) -> int:
        ...
    @property
    def rays(self) -> int:
        ...
    @property
    def seconds(self) -> float:
        ...
class FormFactorOptions:
    """
    Options of compute_form_factors.
    """
    _fields: typing.ClassVar[tuple] = ('quadrature', 'shadow_rays', 'min_value', 'seed', 'threads', 'skip_unneeded')
    def __init__(self, *, quadrature: int = 3, shadow_rays: int = 4, min_value: float = 0.0, seed: int = 0, threads: int = 0, skip_unneeded: bool = True) -> None:
        """
        Options of compute_form_factors. Keywords only: an option left out keeps its default above (the C++ FormFactorOptions{}); an unknown one is a TypeError, a bad value a ValueError naming it.
        
        quadrature: Points on the receiving patch: 1 (centroid), 3 (degree 2) or 7 (degree 5).
        shadow_rays: Visibility rays per quadrature point and source patch; 0 = no occlusion test.
        min_value: Entries below this are dropped (0 keeps every non-zero).
        seed: Seed of the visibility rays.
        threads: Worker threads; 0 = all cores.
        skip_unneeded: Skip visibility rays in a convex enclosure; False traces them all.
        """
    def __repr__(self) -> str:
        ...
    @property
    def min_value(self) -> float:
        """
        Entries below this are dropped (0 keeps every non-zero).
        """
    @property
    def quadrature(self) -> int:
        """
        Points on the receiving patch: 1 (centroid), 3 (degree 2) or 7 (degree 5).
        """
    @property
    def seed(self) -> int:
        """
        Seed of the visibility rays.
        """
    @property
    def shadow_rays(self) -> int:
        """
        Visibility rays per quadrature point and source patch; 0 = no occlusion test.
        """
    @property
    def skip_unneeded(self) -> bool:
        """
        Skip visibility rays in a convex enclosure; False traces them all.
        """
    @property
    def threads(self) -> int:
        """
        Worker threads; 0 = all cores.
        """
class FormFactors:
    """
    Sparse form factors F (CSR) and F^T.
    """
    @staticmethod
    def from_csr(n: typing.SupportsInt | typing.SupportsIndex, indptr: typing.Annotated[numpy.typing.ArrayLike, numpy.uint64], indices: typing.Annotated[numpy.typing.ArrayLike, numpy.uint32], values: typing.Annotated[numpy.typing.ArrayLike, numpy.float32]) -> FormFactors:
        ...
    def checks(self, areas: typing.Annotated[numpy.typing.ArrayLike, numpy.float64]) -> dict:
        """
        Reciprocity A_i F_ij = A_j F_ji and row-sum (closure) summaries.
        """
    def row_sums(self) -> numpy.typing.NDArray[numpy.float64]:
        ...
    @property
    def indices(self) -> numpy.typing.NDArray[numpy.uint32]:
        ...
    @property
    def indptr(self) -> numpy.typing.NDArray[numpy.uint64]:
        ...
    @property
    def n(self) -> int:
        ...
    @property
    def nonzeros(self) -> int:
        ...
    @property
    def values(self) -> numpy.typing.NDArray[numpy.float32]:
        ...
class RadiositySystem:
    """
    M = I - diag(rho) F for 3 channels.
    """
    def __init__(self, form_factors: FormFactors, reflectance: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], areas: typing.Annotated[numpy.typing.ArrayLike, numpy.float64]) -> None:
        ...
    def residual(self, x: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], b: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], dual: bool = False) -> float:
        """
        max |b - M x| / max |b| (M^T when dual).
        """
    @property
    def size(self) -> int:
        ...
class JacobiSolver:
    """
    Jacobi sweeps (gathering); dual=True solves M^T x = b.
    """
    def __init__(self, system: RadiositySystem, rhs: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], dual: bool = False, threads: typing.SupportsInt | typing.SupportsIndex = 0) -> None:
        ...
    def step(self) -> dict:
        ...
    @property
    def iteration(self) -> int:
        ...
    @property
    def residual(self) -> float:
        ...
    @property
    def solution(self) -> numpy.typing.NDArray[numpy.float64]:
        ...
class GaussSeidelSolver:
    """
    Gauss-Seidel sweeps (gathering).
    """
    def __init__(self, system: RadiositySystem, rhs: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], dual: bool = False) -> None:
        ...
    def step(self) -> dict:
        ...
    @property
    def iteration(self) -> int:
        ...
    @property
    def residual(self) -> float:
        ...
    @property
    def solution(self) -> numpy.typing.NDArray[numpy.float64]:
        ...
class SouthwellSolver:
    """
    Southwell / progressive refinement (shooting).
    """
    def __init__(self, system: RadiositySystem, rhs: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], dual: bool = False, shots_per_step: typing.SupportsInt | typing.SupportsIndex = 0) -> None:
        ...
    def step(self) -> dict:
        ...
    @property
    def ambient(self) -> list[float]:
        ...
    @property
    def iteration(self) -> int:
        ...
    @property
    def residual(self) -> float:
        ...
    @property
    def shots(self) -> int:
        ...
    @property
    def solution(self) -> numpy.typing.NDArray[numpy.float64]:
        ...
    @property
    def unshot(self) -> numpy.typing.NDArray[numpy.float64]:
        ...
class DirectSolver:
    """
    Dense LU per channel; solves M x = b and M^T x = b.
    """
    def __init__(self, system: RadiositySystem, threads: typing.SupportsInt | typing.SupportsIndex = 0, progress: typing.Any = None) -> None:
        ...
    def solve(self, rhs: typing.Annotated[numpy.typing.ArrayLike, numpy.float64], dual: bool = False) -> numpy.typing.NDArray[numpy.float64]:
        ...
    @property
    def factor_seconds(self) -> float:
        ...
class RefinementOracle:
    """
    Members:
    
      bf
    
      importance
    """
    __members__: typing.ClassVar[dict[str, RefinementOracle]]
    bf: typing.ClassVar[RefinementOracle]
    importance: typing.ClassVar[RefinementOracle]
    @typing.overload
    def __eq__(self, other: RefinementOracle) -> bool:
        ...
    @typing.overload
    def __eq__(self, other: typing.Any) -> bool:
        ...
    def __getstate__(self) -> int:
        ...
    def __hash__(self) -> int:
        ...
    def __index__(self) -> int:
        ...
    def __init__(self, value: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __int__(self) -> int:
        ...
    @typing.overload
    def __ne__(self, other: RefinementOracle) -> bool:
        ...
    @typing.overload
    def __ne__(self, other: typing.Any) -> bool:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, state: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    def __str__(self) -> str:
        ...
    @property
    def name(self) -> str:
        ...
    @property
    def value(self) -> int:
        ...
class HierarchicalOptions:
    """
    Options of HierarchicalSolver.
    """
    _fields: typing.ClassVar[tuple] = ('oracle', 'epsilon', 'min_area', 'shadow_rays', 'sweeps', 'tolerance', 'max_links', 'seed', 'threads', 'skip_unneeded')
    def __init__(self, *, oracle: RefinementOracle | str = ..., epsilon: float = 0.001, min_area: float = 0.0, shadow_rays: int = 1, sweeps: int = 30, tolerance: float = 1e-06, max_links: int = 20000000, seed: int = 0, threads: int = 0, skip_unneeded: bool = True) -> None:
        """
        Options of HierarchicalSolver. Keywords only: an option left out keeps its default above (the C++ HierarchicalOptions{}); an unknown one is a TypeError, a bad value a ValueError naming it.
        
        oracle: Which links to refine: by BF or by importance.
        epsilon: Refinement threshold, relative: of the brightest emission (BF) or of the measurement (importance).
        min_area: Elements are not split below this area; 0 = 1e-4 of the largest input triangle.
        shadow_rays: Visibility rays per receiver quadrature point (7 per link) and per estimate (2).
        sweeps: Gauss-Seidel sweeps per step at most.
        tolerance: Relative change per sweep that ends a step's sweeps.
        max_links: Refinement stops before exceeding this many links.
        seed: Seed of the visibility rays.
        threads: Worker threads; 0 = all cores.
        skip_unneeded: Skip visibility rays in a convex enclosure; False traces them all.
        """
    def __repr__(self) -> str:
        ...
    @property
    def epsilon(self) -> float:
        """
        Refinement threshold, relative: of the brightest emission (BF) or of the measurement (importance).
        """
    @property
    def max_links(self) -> int:
        """
        Refinement stops before exceeding this many links.
        """
    @property
    def min_area(self) -> float:
        """
        Elements are not split below this area; 0 = 1e-4 of the largest input triangle.
        """
    @property
    def oracle(self) -> RefinementOracle:
        """
        Which links to refine: by BF or by importance.
        """
    @property
    def seed(self) -> int:
        """
        Seed of the visibility rays.
        """
    @property
    def shadow_rays(self) -> int:
        """
        Visibility rays per receiver quadrature point (7 per link) and per estimate (2).
        """
    @property
    def skip_unneeded(self) -> bool:
        """
        Skip visibility rays in a convex enclosure; False traces them all.
        """
    @property
    def sweeps(self) -> int:
        """
        Gauss-Seidel sweeps per step at most.
        """
    @property
    def threads(self) -> int:
        """
        Worker threads; 0 = all cores.
        """
    @property
    def tolerance(self) -> float:
        """
        Relative change per sweep that ends a step's sweeps.
        """
class HierarchicalSolver:
    """
    Hierarchical radiosity and importance (HSA91, SAS92); stepped.
    """
    def __init__(self, scene: Scene, receiver_prim: typing.Annotated[numpy.typing.ArrayLike, numpy.uint32], receiver_b1: typing.Annotated[numpy.typing.ArrayLike, numpy.float32], receiver_b2: typing.Annotated[numpy.typing.ArrayLike, numpy.float32], receiver_weight: typing.SupportsFloat | typing.SupportsIndex, options: HierarchicalOptions, progress: typing.Any = None, albedo: typing.Any = None) -> None:
        ...
    def leaves(self) -> dict:
        ...
    def link_coverage_error(self, only_facing_roots: bool = True) -> float:
        """
        Largest |covered / area - 1| of any root as seen from any leaf (0: no source missed or doubled).
        """
    def links(self) -> dict:
        ...
    def measurements(self) -> tuple[typing.Annotated[list[float], "FixedSize(3)"], typing.Annotated[list[float], "FixedSize(3)"]]:
        ...
    def step(self, progress: typing.Any = None) -> dict:
        ...
    @property
    def total_rays(self) -> int:
        ...
    @property
    def total_rays_skipped(self) -> int:
        ...
class Guide:
    """
    A trained SD-tree guide (guiding/sd_tree.h): a spatial binary tree with a quadtree of directions in each leaf.
    """
    def directional(self, x: typing.SupportsFloat | typing.SupportsIndex, y: typing.SupportsFloat | typing.SupportsIndex, z: typing.SupportsFloat | typing.SupportsIndex) -> numpy.typing.NDArray[numpy.float32]:
        """
        The quadtree at a point: rows (u0, v0, size, density on the unit square); u = (cos theta + 1) / 2, v = phi / (2 pi); solid-angle density = density / (4 pi).
        """
    def leaves(self) -> dict:
        """
        The spatial leaves: dict(lo, hi, directional_nodes, total, bsdf_fraction).
        """
    def pdf(self, points: typing.Annotated[numpy.typing.ArrayLike, numpy.float32], directions: typing.Annotated[numpy.typing.ArrayLike, numpy.float32]) -> numpy.typing.NDArray[numpy.float32]:
        """
        Solid-angle density of each direction (N, 3) at its point (N, 3); 0 where the leaf learnt nothing.
        """
    def sample(self, points: typing.Annotated[numpy.typing.ArrayLike, numpy.float32], u: typing.Annotated[numpy.typing.ArrayLike, numpy.float32]) -> numpy.typing.NDArray[numpy.float32]:
        """
        A unit direction per point (N, 3) from u (N, 2) in [0, 1); NaN where the leaf learnt nothing.
        """
    @property
    def empty(self) -> bool:
        ...
    @property
    def stats(self) -> dict:
        ...
def cast_random_rays(scene: Scene, camera: PinholeCamera, n_rays: typing.SupportsInt | typing.SupportsIndex, seed: typing.SupportsInt | typing.SupportsIndex = 0, threads: typing.SupportsInt | typing.SupportsIndex = 0) -> dict:
    """
    Embree-only cast of incoherent rays (no shading): the ray-tracing limit for this scene.
    """
def compute_form_factors(patches: Scene, options: FormFactorOptions, progress: typing.Any = None, *, scatters: typing.Annotated[numpy.typing.ArrayLike, numpy.uint8] | None = None, receivers: typing.Annotated[numpy.typing.ArrayLike, numpy.uint8] | None = None) -> tuple[FormFactors, dict]:
    """
    Form factors between the triangles of `patches` (one patch each): (FormFactors, stats). Every row, or with scatters (rho > 0 per patch) only rows of patches that reflect, and with receivers (R > 0 per patch) only those of non-zero importance for that view (form_factors.h).
    """
def direct_irradiance(patches: Scene, points_per_axis: typing.SupportsInt | typing.SupportsIndex = 4, env_strata: typing.SupportsInt | typing.SupportsIndex = 8, seed: typing.SupportsInt | typing.SupportsIndex = 0, threads: typing.SupportsInt | typing.SupportsIndex = 0, progress: typing.Any = None) -> numpy.typing.NDArray[numpy.float64]:
    """
    Mean irradiance (N, 3) over each patch of `patches` (one triangle each) from its point, spot and directional lights and its environment (env_strata^2 pairs of directions per point), with visibility, at the centroids of an n x n split of the patch (radiosity/direct_irradiance.h).
    """
@typing.overload
def finish_chains(scene: Scene, camera: PinholeCamera, options: PssmltOptions, start: ChainStartUp, parts: collections.abc.Sequence[ChainPart], keyboard_interrupt: bool = False) -> dict:
    """
    The render's result dict (as render_mlt / render_pssmlt) from its start-up and chain parts, given in chain order; stats.seconds is the start-up's plus the parts' (the caller knows the wall time).
    """
@typing.overload
def finish_chains(scene: Scene, camera: PinholeCamera, options: MltOptions, start: ChainStartUp, parts: collections.abc.Sequence[ChainPart], keyboard_interrupt: bool = False) -> dict:
    """
    The render's result dict (as render_mlt / render_pssmlt) from its start-up and chain parts, given in chain order; stats.seconds is the start-up's plus the parts' (the caller knows the wall time).
    """
def fresnel_dielectric(cos_i: typing.Annotated[numpy.typing.ArrayLike, numpy.float32], eta: typing.SupportsFloat | typing.SupportsIndex) -> tuple[numpy.typing.NDArray[numpy.float32], numpy.typing.NDArray[numpy.float32], numpy.typing.NDArray[numpy.float32]]:
    """
    Unpolarised Fresnel reflectance of a smooth interface with eta = interior / exterior IOR; cos_i < 0 arrives from the interior. Returns (R, |cos_t|, eta_ratio = IOR of the refracted side / incident side).
    """
def guide_from_records(scene: Scene, records: typing.Annotated[numpy.typing.ArrayLike, numpy.float32], bsdf_fraction: typing.SupportsFloat | typing.SupportsIndex = 0.5, spatial_threshold: typing.SupportsInt | typing.SupportsIndex = 1000, rho: typing.SupportsFloat | typing.SupportsIndex = 0.009999999776482582) -> Guide:
    """
    A guide over the scene's box from records (N, 7): x, y, z, wx, wy, wz, value (the incident quantity over the density the direction was drawn with), sampled with probability 1 - bsdf_fraction in every leaf.
    """
def point_polygon_form_factor(point: typing.Annotated[collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], "FixedSize(3)"], normal: typing.Annotated[collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], "FixedSize(3)"], polygon: typing.Annotated[numpy.typing.ArrayLike, numpy.float32]) -> float:
    """
    Unoccluded form factor from a differential area to a planar convex polygon (3-8 vertices) whose right-hand-rule normal faces the point; 0 if it faces away.
    """
def read_image(path: str) -> tuple[numpy.typing.NDArray[numpy.float32], dict[str, str], bool]:
    """
    Reads an image: (H x W x C float32 pixels, metadata dict, is_low_dynamic_range).
    """
def render_bdpt(scene: Scene, camera: PinholeCamera, options: BdptOptions, progress: typing.Any = None, accumulators: bool = False) -> dict:
    """
    Bidirectional path tracing; returns dict(mean, variance, counts, light_paths, stats, strategies, keyboard_interrupt); strategies maps (s, t) to MIS-weighted images when asked for.
    """
def render_light(scene: Scene, camera: PinholeCamera, options: LightTracerOptions, progress: typing.Any = None, accumulators: bool = False) -> dict:
    """
    Light-traces the scene (spp x pixels particles); returns dict(mean, variance, counts, light_paths, stats, keyboard_interrupt).
    """
def render_mlt(scene: Scene, camera: PinholeCamera, options: MltOptions, progress: typing.Any = None) -> dict:
    """
    Path-space MLT (Veach); returns dict(mean, variance=None, light_paths (= mutations), stats, keyboard_interrupt); stats has b, b_ci95, mutations, acceptance rates and per mutation type counts.
    """
def render_path(scene: Scene, camera: PinholeCamera, options: PathTracerOptions, progress: typing.Any = None, accumulators: bool = False) -> dict:
    """
    Path-traces the scene; returns dict(mean, variance, counts, stats, keyboard_interrupt). progress(done, total) is called about every 100 ms.
    """
def render_pssmlt(scene: Scene, camera: PinholeCamera, options: PssmltOptions, progress: typing.Any = None) -> dict:
    """
    Primary-sample-space MLT over BDPT; returns dict(mean, variance=None, light_paths (= mutations), stats, keyboard_interrupt); stats has b, b_ci95, mutations and acceptance rates, and when multiplexed b_per_depth, b_per_depth_ci95 and mutations_per_depth (indexed by path length).
    """
@typing.overload
def run_chains(scene: Scene, camera: PinholeCamera, options: PssmltOptions, start: ChainStartUp, first_chain: typing.SupportsInt | typing.SupportsIndex, chain_count: typing.SupportsInt | typing.SupportsIndex, progress: typing.Any = None) -> ChainPart:
    """
    Chains [first_chain, first_chain + chain_count) of a start-up; its `interrupted` is True after Ctrl-C.
    """
@typing.overload
def run_chains(scene: Scene, camera: PinholeCamera, options: MltOptions, start: ChainStartUp, first_chain: typing.SupportsInt | typing.SupportsIndex, chain_count: typing.SupportsInt | typing.SupportsIndex, progress: typing.Any = None) -> ChainPart:
    """
    Chains [first_chain, first_chain + chain_count) of a start-up; its `interrupted` is True after Ctrl-C.
    """
@typing.overload
def start_chains(scene: Scene, camera: PinholeCamera, options: PssmltOptions, progress: typing.Any = None) -> ChainStartUp:
    """
    The start-up of an MLT render (direct light, pilot, bootstrap, chain starts), run once; its `cancelled` is True after Ctrl-C.
    """
@typing.overload
def start_chains(scene: Scene, camera: PinholeCamera, options: MltOptions, progress: typing.Any = None) -> ChainStartUp:
    """
    The start-up of an MLT render (direct light, pilot, bootstrap, chain starts), run once; its `cancelled` is True after Ctrl-C.
    """
def trace_camera_hits(scene: Scene, camera: PinholeCamera, samples_per_axis: typing.SupportsInt | typing.SupportsIndex = 2, seed: typing.SupportsInt | typing.SupportsIndex = 0, threads: typing.SupportsInt | typing.SupportsIndex = 0) -> tuple[numpy.typing.NDArray[numpy.int32], numpy.typing.NDArray[numpy.float32]]:
    """
    Triangle hit by each stratified camera sample, (H x W x S int32, -1 = miss) and its barycentrics.
    """
def train_importance_guide(scene: Scene, camera: PinholeCamera, options: LightTracerOptions, progress: typing.Any = None) -> dict:
    """
    Trains the importance guide the light tracer would; returns dict(guide, keyboard_interrupt).
    """
def train_radiance_guide(scene: Scene, camera: PinholeCamera, options: PathTracerOptions, progress: typing.Any = None) -> dict:
    """
    Trains the radiance guide the path tracer would (options.guiding need not be set); returns dict(guide, keyboard_interrupt).
    """
@typing.overload
def with_guide_start(options: PathTracerOptions, radiance: Guide, importance: Guide) -> PathTracerOptions:
    """
    A copy of options whose guide training starts from these guides (None: from BSDF sampling).
    """
@typing.overload
def with_guide_start(options: LightTracerOptions, radiance: Guide, importance: Guide) -> LightTracerOptions:
    """
    A copy of options whose guide training starts from these guides (None: from BSDF sampling).
    """
@typing.overload
def with_guide_start(options: BdptOptions, radiance: Guide, importance: Guide) -> BdptOptions:
    """
    A copy of options whose guide training starts from these guides (None: from BSDF sampling).
    """
def write_image(path: str, pixels: typing.Annotated[numpy.typing.ArrayLike, numpy.float32], metadata: collections.abc.Mapping[str, str] = {}) -> None:
    """
    Writes an H x W x C float image; 8-bit formats expect values already in [0, 1].
    """
BLOCK_SPP: int = 16
MAX_DIRECT_PATCHES: int = 12000
MAX_GUIDE_RECORDS: int = 16777216
