" Vim syntax file for ptsc .pts scenes. Keyword lists are tested against
" grammar/pts.pest, parameter names against the checker's schemas, by
" tests/integration/editors.rs (`min`, `max` and `clamp` are functions here).
if exists("b:current_syntax")
  finish
endif

syn keyword ptsControl let include for in if else fn group instance
syn keyword ptsBlock render camera environment sky atmosphere background material texture sphere plane quad disk triangle box cylinder cone torus capsule mesh point_light spot_light directional_light
syn keyword ptsColour rgb
syn keyword ptsBoolean true false
" The predefined names of an animation.
syn keyword ptsPredefined frame clock clock_delta pi x y z
syn keyword ptsParam absorption albedo ambient angle anisotropic anisotropy aperture axis base base_color base_radius bump bump_height center channel clearcoat clearcoat_roughness color_space corner density diffuse direction edge1 edge2 emission eta even exposure file focus_distance fov frequency gloss high hotspot hybrid_weight integrator intensity ior ior_outside irradiance k lambda light_samples light_sampling light_selection look_at low major_radius materials matrix max_depth medium_color metallic min_samples minor_radius multiscatter node noise_threshold normal normal_map normal_scale octaves odd omega opacity opacity_cutoff open output phase point position preset radius reflection resolution rotate roughness rr_depth sampler samples scale scattering seed sheen sheen_tint shutter smooth space specular specular_tint stop sun_azimuth sun_direction sun_elevation sun_intensity time top top_radius translate transmission turbidity turbulence two_sided type up v0 v1 v2 velocity vertex_color wrap
syn keyword ptsWord path bdpt ptlt whitted hybrid normals albedo depth uv object world checker image noise turbulence marble wood gradient stripes repeat clamp mirror mix conductor plastic dielectric thin_dielectric gold silver copper aluminium chromium auto bvh exhaustive power uniform sobol independent
syn keyword ptsFunction sin cos tan asin acos atan2 sqrt pow exp log abs min max clamp floor ceil round int mod radians degrees normalize length dot cross len str rand
" 1, 2.5, 1e-3 and .5, but not the .. of a range (0..10).
syn match ptsNumber "\%(\<\d\+\%(\.\.\@!\d*\)\=\|\%([.0-9]\)\@<!\.\d\+\)\%([eE][+-]\=\d\+\)\=\>"
syn region ptsString start=+"+ skip=+\\.+ end=+"\|$+
syn match ptsComment "//.*$"
syn region ptsComment start="/\*" end="\*/"

hi def link ptsControl Statement
hi def link ptsBlock Type
hi def link ptsColour Function
hi def link ptsBoolean Boolean
hi def link ptsPredefined Constant
hi def link ptsFunction Function
hi def link ptsParam Identifier
hi def link ptsWord Constant
hi def link ptsNumber Number
hi def link ptsString String
hi def link ptsComment Comment

let b:current_syntax = "pts"
