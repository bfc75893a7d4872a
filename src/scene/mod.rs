//! A fixed-capacity scene — spheres, and where its type allows them lights, planes
//! and mirrors — and the closest-hit search for one ray (through the one dispatch,
//! like the renderer).

pub mod light;
pub mod material;
pub mod plane;
pub mod sphere;

use embedded_graphics::pixelcolor::Rgb888;
use heapless::Vec;

use crate::error::{ObjectRef, SceneError, SettingsError};
use crate::scene::light::Light;
use crate::scene::material::Material;
use crate::scene::plane::Plane;
use crate::scene::sphere::Sphere;

/// The largest reflection depth any scene type can ask for (`D ≤ MAX_DEPTH` is what
/// scene files accept; a larger `D` is clamped to it).
pub const MAX_DEPTH: u8 = 8;

/// Scene-wide shading settings.
///
/// ```
/// use embedded_raytracer::Settings;
/// let s = Settings::DEFAULT;
/// assert_eq!((s.ambient, s.max_depth, s.shadows), (0.1, 2, true));
/// assert!(s.with_ambient(1.5).check().is_err());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct Settings {
    /// Light every lit surface gets regardless of the lights, `0 … 1` (default 0.1).
    ///
    /// Not used without lights (Lab #1 has its own 0.3 floor).
    pub ambient: f32,
    /// How many times a ray may be reflected (default 2; at most the scene type's `D`
    /// and [`MAX_DEPTH`]).
    ///
    /// At this depth a mirror shows the background colour.
    pub max_depth: u8,
    /// Whether lights cast shadows (default true).
    pub shadows: bool,
}

impl Settings {
    /// Ambient 0.1, depth 2, shadows on.
    pub const DEFAULT: Settings = Settings {
        ambient: 0.1,
        max_depth: 2,
        shadows: true,
    };

    /// The same settings with ambient light `ambient`.
    #[must_use]
    pub const fn with_ambient(mut self, ambient: f32) -> Self {
        self.ambient = ambient;
        self
    }

    /// The same settings with reflection depth `max_depth`.
    #[must_use]
    pub const fn with_max_depth(mut self, max_depth: u8) -> Self {
        self.max_depth = max_depth;
        self
    }

    /// The same settings with shadows on or off.
    #[must_use]
    pub const fn with_shadows(mut self, shadows: bool) -> Self {
        self.shadows = shadows;
        self
    }

    /// The settings if `ambient` is in `[0, 1]` and `max_depth ≤` [`MAX_DEPTH`].
    pub const fn check(self) -> Result<Self, SettingsError> {
        if !(self.ambient >= 0.0 && self.ambient <= 1.0) {
            return Err(SettingsError::Ambient);
        }
        if self.max_depth > MAX_DEPTH {
            return Err(SettingsError::MaxDepth { max: MAX_DEPTH });
        }
        Ok(self)
    }
}

impl Default for Settings {
    fn default() -> Self {
        Settings::DEFAULT
    }
}

/// Up to `N` spheres, `L` lights and `P` planes, mirrors reflected up to `D` times, and
/// a background colour.
///
/// No allocation: everything lives inline in `heapless::Vec`s.
///
/// The capacities are what a scene type pays for: `Scene<N>` (`L = P = D = 0`) is
/// spheres under the lecture notes' Lab #1 headlight and renders through exactly that loop;
/// lights bring Phong shading and shadow rays, planes a floor, `D ≥ 1` the mirror loop.
///
/// A scene can be a `static` in flash:
///
/// ```
/// use embedded_graphics::pixelcolor::Rgb888;
/// use embedded_raytracer::{Scene, Sphere, Vec3};
///
/// static SCENE: Scene<2> = Scene::from_array(
///     [
///         Sphere::new(Vec3::new(0.0, 0.0, 0.0), 1.0, Rgb888::new(255, 64, 64)),
///         Sphere::new(Vec3::new(1.5, 0.0, -2.0), 1.0, Rgb888::new(64, 255, 64)),
///     ],
///     Rgb888::new(0, 0, 0),
/// );
/// assert_eq!(SCENE.spheres().len(), 2);
/// ```
///
/// and so can one with lights, a floor and mirrors:
///
/// ```
/// use embedded_graphics::pixelcolor::Rgb888;
/// use embedded_raytracer::{Light, Material, Plane, Scene, Settings, Sphere, Vec3};
///
/// static LIT: Scene<1, 1, 1, 2> = Scene::from_arrays(
///     [Sphere::new(Vec3::new(0.0, 0.0, 0.0), 1.0, Rgb888::new(255, 64, 64))
///         .with_material(Material::new(0.5, 32.0, 0.3))],
///     [Light::directional(Vec3::new(-1.0, -2.0, -1.0), 0.8)],
///     [Plane::new(Vec3::new(0.0, -1.0, 0.0), Vec3::new(0.0, 1.0, 0.0), Rgb888::new(220, 220, 220))
///         .with_checker(Rgb888::new(40, 40, 40), 1.0)],
///     Rgb888::new(0, 0, 0),
///     Settings::DEFAULT,
/// );
/// assert_eq!(LIT.planes().len(), 1);
/// assert_eq!(LIT.max_depth(), 2);
/// ```
#[derive(Clone, Debug)]
pub struct Scene<const N: usize, const L: usize = 0, const P: usize = 0, const D: usize = 0> {
    spheres: Vec<Sphere, N>,
    lights: Vec<Light, L>,
    planes: Vec<Plane, P>,
    background: Rgb888,
    settings: Settings,
}

/// A ray's closest hit: which object and the ray parameter `t` (`point = eye + t·d`).
///
/// Objects are numbered spheres first ([`Scene::spheres`]), then planes: a plane hit
/// has `index = spheres().len() + k` for the `k`-th plane.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct Hit {
    /// Index of the object hit (spheres, then planes).
    pub index: usize,
    /// Ray parameter of the hit, `> 0`.
    pub t: f32,
}

impl<const N: usize, const L: usize, const P: usize, const D: usize> Scene<N, L, P, D> {
    /// Whether the type has anything beyond Lab #1 spheres (lights, planes or mirrors):
    /// decided at compile time, so `Scene<N>` links only the Lab #1 loop.
    pub(crate) const FEATURES: bool = L > 0 || P > 0 || D > 0;

    /// The default settings with the depth the type allows (`min(2, D)`).
    const DEFAULT_SETTINGS: Settings = Settings {
        max_depth: if D < 2 { D as u8 } else { 2 },
        ..Settings::DEFAULT
    };

    /// An empty scene.
    #[must_use]
    pub const fn new(background: Rgb888) -> Self {
        Self {
            spheres: Vec::new(),
            lights: Vec::new(),
            planes: Vec::new(),
            background,
            settings: Self::DEFAULT_SETTINGS,
        }
    }

    /// A scene from an array of `M ≤ N` spheres, usable in a `static` (`M > N` is a
    /// compile-time error).
    ///
    /// The spheres are not checked: build them with
    /// [`Sphere::try_new`] in a const context to have bad numbers rejected at compile
    /// time.
    #[must_use]
    pub const fn from_array<const M: usize>(spheres: [Sphere; M], background: Rgb888) -> Self {
        Self {
            spheres: Vec::from_array(spheres),
            lights: Vec::new(),
            planes: Vec::new(),
            background,
            settings: Self::DEFAULT_SETTINGS,
        }
    }

    /// A scene from arrays of spheres, lights and planes (each within its capacity, a
    /// compile-time error otherwise) and settings, usable in a `static`.
    ///
    /// Like every
    /// const constructor it checks nothing: [`Scene::check`] applies the rules of the
    /// checked path ([`push`](Self::push), [`set_settings`](Self::set_settings)) to the
    /// whole scene. The reflection depth has one rule: a `max_depth` above `D` (or
    /// [`MAX_DEPTH`]) is an error where anything is checked; unchecked, the render
    /// never traces deeper than the type can hold ([`Scene::max_depth`]).
    #[must_use]
    pub const fn from_arrays<const MS: usize, const ML: usize, const MP: usize>(
        spheres: [Sphere; MS],
        lights: [Light; ML],
        planes: [Plane; MP],
        background: Rgb888,
        settings: Settings,
    ) -> Self {
        Self {
            spheres: Vec::from_array(spheres),
            lights: Vec::from_array(lights),
            planes: Vec::from_array(planes),
            background,
            settings,
        }
    }

    /// A mirror needs a type with reflection depth.
    fn check_mirror(material: &Material) -> Result<(), SceneError> {
        if D == 0 && material.reflect > 0.0 {
            Err(SceneError::MirrorWithoutDepth)
        } else {
            Ok(())
        }
    }

    /// Adds a sphere after checking it ([`Sphere::check`]'s rules; a mirror needs
    /// `D ≥ 1`).
    pub fn push(&mut self, sphere: Sphere) -> Result<(), SceneError> {
        let sphere = sphere.check()?;
        Self::check_mirror(&sphere.material)?;
        self.spheres
            .push(sphere)
            .map_err(|_| SceneError::Full { capacity: N })
    }

    /// Adds a light after checking it ([`Light::check`]).
    pub fn push_light(&mut self, light: Light) -> Result<(), SceneError> {
        let light = light.check()?;
        self.lights
            .push(light)
            .map_err(|_| SceneError::TooManyLights { capacity: L })
    }

    /// Adds a plane after checking it ([`Plane::check`]; a mirror needs `D ≥ 1`).
    pub fn push_plane(&mut self, plane: Plane) -> Result<(), SceneError> {
        let plane = plane.check()?;
        Self::check_mirror(&plane.material)?;
        self.planes
            .push(plane)
            .map_err(|_| SceneError::TooManyPlanes { capacity: P })
    }

    /// Replaces sphere `index` after the checks of [`push`](Self::push): what an
    /// animation calls every frame to move, resize or recolour a sphere.
    ///
    /// On an error the scene is as it was.
    ///
    /// ```
    /// use embedded_graphics::pixelcolor::Rgb888;
    /// use embedded_raytracer::{ObjectRef, Scene, SceneError, Sphere, Vec3};
    ///
    /// let ball = Sphere::new(Vec3::new(0.0, 1.0, 0.0), 0.5, Rgb888::new(255, 64, 64));
    /// let mut scene: Scene<1> = Scene::from_array([ball], Rgb888::new(0, 0, 0));
    /// scene.set_sphere(0, Sphere { center: Vec3::new(0.0, 0.6, 0.0), ..ball })?;
    /// assert_eq!(scene.spheres()[0].center.y, 0.6);
    /// assert_eq!(scene.set_sphere(1, ball), Err(SceneError::NoSuchObject(ObjectRef::Sphere(1))));
    /// # Ok::<(), SceneError>(())
    /// ```
    pub fn set_sphere(&mut self, index: usize, sphere: Sphere) -> Result<(), SceneError> {
        let sphere = sphere.check()?;
        Self::check_mirror(&sphere.material)?;
        let slot = self
            .spheres
            .get_mut(index)
            .ok_or(SceneError::NoSuchObject(ObjectRef::Sphere(index)))?;
        *slot = sphere;
        Ok(())
    }

    /// Replaces light `index` after the checks of [`push_light`](Self::push_light).
    pub fn set_light(&mut self, index: usize, light: Light) -> Result<(), SceneError> {
        let light = light.check()?;
        let slot = self
            .lights
            .get_mut(index)
            .ok_or(SceneError::NoSuchObject(ObjectRef::Light(index)))?;
        *slot = light;
        Ok(())
    }

    /// Replaces plane `index` after the checks of [`push_plane`](Self::push_plane).
    pub fn set_plane(&mut self, index: usize, plane: Plane) -> Result<(), SceneError> {
        let plane = plane.check()?;
        Self::check_mirror(&plane.material)?;
        let slot = self
            .planes
            .get_mut(index)
            .ok_or(SceneError::NoSuchObject(ObjectRef::Plane(index)))?;
        *slot = plane;
        Ok(())
    }

    /// Sets the settings after checking them ([`Settings::check`], and
    /// `max_depth ≤ D`).
    pub fn set_settings(&mut self, settings: Settings) -> Result<(), SceneError> {
        self.settings = Self::check_settings(settings)?;
        Ok(())
    }

    /// [`Settings::check`], and `max_depth ≤ D`: the one rule of the reflection depth.
    fn check_settings(settings: Settings) -> Result<Settings, SceneError> {
        let settings = settings.check()?;
        if usize::from(settings.max_depth) > D {
            return Err(SettingsError::MaxDepth {
                max: if D < MAX_DEPTH as usize {
                    D as u8
                } else {
                    MAX_DEPTH
                },
            }
            .into());
        }
        Ok(settings)
    }

    /// The scene if every object, the settings and the reflection depth pass the checks
    /// of [`push`](Self::push), [`push_light`](Self::push_light),
    /// [`push_plane`](Self::push_plane) and [`set_settings`](Self::set_settings): what a
    /// scene built unchecked ([`Scene::from_arrays`]) is told, for instance in a test.
    ///
    /// ```
    /// use embedded_graphics::pixelcolor::Rgb888;
    /// use embedded_raytracer::{Scene, SceneError, Settings, SettingsError};
    ///
    /// // Depth 3 in a type that reflects at most twice: traced as 2, refused by the check.
    /// let scene: Scene<0, 0, 0, 2> =
    ///     Scene::from_arrays([], [], [], Rgb888::new(0, 0, 0), Settings::DEFAULT.with_max_depth(3));
    /// assert_eq!(scene.max_depth(), 2);
    /// assert_eq!(scene.check(), Err(SceneError::Settings(SettingsError::MaxDepth { max: 2 })));
    /// ```
    pub fn check(&self) -> Result<(), SceneError> {
        for sphere in self.spheres() {
            Self::check_mirror(&sphere.check()?.material)?;
        }
        for light in self.lights() {
            light.check()?;
        }
        for plane in self.planes() {
            Self::check_mirror(&plane.check()?.material)?;
        }
        Self::check_settings(self.settings).map(|_| ())
    }

    /// The spheres, in the order they were added.
    #[must_use]
    pub fn spheres(&self) -> &[Sphere] {
        &self.spheres
    }

    /// The lights, in the order they were added.
    #[must_use]
    pub fn lights(&self) -> &[Light] {
        &self.lights
    }

    /// The planes, in the order they were added.
    #[must_use]
    pub fn planes(&self) -> &[Plane] {
        &self.planes
    }

    /// The settings.
    #[must_use]
    pub const fn settings(&self) -> Settings {
        self.settings
    }

    /// The reflection depth traced: `settings().max_depth`, at most `D` and
    /// [`MAX_DEPTH`].
    #[must_use]
    pub const fn max_depth(&self) -> u8 {
        let mut d = self.settings.max_depth;
        if d as usize > D {
            d = D as u8;
        }
        if d > MAX_DEPTH {
            d = MAX_DEPTH;
        }
        d
    }

    /// The colour of rays that hit nothing.
    #[must_use]
    pub const fn background(&self) -> Rgb888 {
        self.background
    }

    /// Sets the background colour.
    pub fn set_background(&mut self, background: Rgb888) {
        self.background = background;
    }
}
