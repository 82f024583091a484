// The colour of a path: twin of prismatic_core::model::bands::BandTable's
// `rgb_of_flux`, `hue` and `reflectance`, and of model::wavelength_rgb and
// model::reflectance. The band buffer holds the N bands, then the rows of
// the colour of each wavelength, then as many rows of the three reflectance
// primaries (`weight` only), which paths read when
// `params.colour_by_wavelength`.

// WavelengthRgb::at
fn wavelength_rgb(lambda_nm: f32) -> vec3<f32> {
    let x = (lambda_nm - WAVELENGTH_RGB_FIRST_NM) / WAVELENGTH_RGB_STEP_NM;
    if !(x >= 0.0 && x <= f32(WAVELENGTH_RGB_ROWS - 1u)) {
        return vec3<f32>(0.0);
    }
    let i = min(u32(x), WAVELENGTH_RGB_ROWS - 2u);
    let f = x - f32(i);
    let a = bands[params.band_count + i].weight;
    let b = bands[params.band_count + i + 1u].weight;
    return a + (b - a) * f;
}

// BandTable::rgb_of_flux: flux carried by a path of `band` at `lambda_nm`.
fn rgb_of_flux(band: u32, lambda_nm: f32, flux: f32) -> vec3<f32> {
    if band >= params.band_count {
        return vec3<f32>(flux);
    }
    if params.colour_by_wavelength != 0u {
        return wavelength_rgb(lambda_nm) * flux;
    }
    return bands[band].weight * (flux * f32(params.band_count));
}

// ReflectancePrimaries::at: the three primaries' reflectances at `lambda_nm`.
fn primaries_at(lambda_nm: f32) -> vec3<f32> {
    let last = f32(WAVELENGTH_RGB_ROWS - 1u);
    let x = clamp((lambda_nm - WAVELENGTH_RGB_FIRST_NM) / WAVELENGTH_RGB_STEP_NM, 0.0, last);
    let i = min(u32(x), WAVELENGTH_RGB_ROWS - 2u);
    let f = x - f32(i);
    let a = bands[params.band_count + WAVELENGTH_RGB_ROWS + i].weight;
    let b = bands[params.band_count + WAVELENGTH_RGB_ROWS + i + 1u].weight;
    return a + (b - a) * f;
}

// BandTable::reflectance: what a surface of `albedo` reflects of a path
// of `band` at `lambda_nm`, per channel of the path's colour.
fn reflectance(albedo: vec3<f32>, band: u32, lambda_nm: f32) -> vec3<f32> {
    let grey = albedo.x == albedo.y && albedo.y == albedo.z;
    if params.colour_by_wavelength == 0u || band >= params.band_count || grey {
        return albedo;
    }
    return vec3<f32>(dot(albedo, primaries_at(lambda_nm)));
}

// BandTable::bounce_reflectance: the share of a path's flux a diffuse
// surface reflects (indirect light's Russian roulette).
fn bounce_reflectance(albedo: vec3<f32>, band: u32, lambda_nm: f32) -> f32 {
    if albedo.x == albedo.y && albedo.y == albedo.z {
        return clamp(albedo.x, 0.0, 1.0);
    }
    if params.colour_by_wavelength != 0u && band < params.band_count {
        return clamp(dot(albedo, primaries_at(lambda_nm)), 0.0, 1.0);
    }
    let colour = max(rgb_of_flux(band, lambda_nm, 1.0), vec3<f32>(0.0));
    let total = colour.x + colour.y + colour.z;
    if total > 0.0 {
        return clamp(dot(colour, albedo) / total, 0.0, 1.0);
    }
    return clamp((albedo.x + albedo.y + albedo.z) / 3.0, 0.0, 1.0);
}

// BandTable::hue: what one path adds to the paper estimator's W.
fn hue(band: u32, lambda_nm: f32) -> vec3<f32> {
    if band >= params.band_count {
        return vec3<f32>(1.0);
    }
    if params.colour_by_wavelength != 0u {
        return wavelength_rgb(lambda_nm) / f32(params.band_count);
    }
    return bands[band].weight;
}
