//! The coefficients of RODAS (Hairer & Wanner, *Solving ODEs II*, Section VI.4; their
//! code's ROCOE, method 1), in the transformed variables uᵢ, and as the rows the
//! stepper loops over.

/// γ: the diagonal of the method (–); W = I/(hγ) − J.
pub(super) const GAMMA: f64 = 0.25;
const C2: f64 = 0.386;
const C3: f64 = 0.21;
const C4: f64 = 0.63;
const D1: f64 = 0.25;
const D2: f64 = -0.1043;
const D3: f64 = 0.1035;
const D4: f64 = -0.0362;

const A21: f64 = 1.544;
const A31: f64 = 0.946_678_528_081_582_6;
const A32: f64 = 0.255_701_169_898_328_4;
const A41: f64 = 3.314_825_187_068_521;
const A42: f64 = 2.896_124_015_972_201;
const A43: f64 = 0.998_641_913_997_781_7;
const A51: f64 = 1.221_224_509_226_641;
const A52: f64 = 6.019_134_481_288_629;
const A53: f64 = 12.537_083_329_320_87;
const A54: f64 = -0.687_886_036_105_895;

const C21: f64 = -5.6688;
const C31: f64 = -2.430_093_356_833_875;
const C32: f64 = -0.206_359_915_709_191_5;
const C41: f64 = -0.107_352_905_815_137_5;
const C42: f64 = -9.594_562_251_023_355;
const C43: f64 = -20.470_286_148_096_16;
const C51: f64 = 7.496_443_313_967_647;
const C52: f64 = -10.246_804_314_643_52;
const C53: f64 = -33.999_903_528_199_05;
const C54: f64 = 11.708_908_932_061_6;
const C61: f64 = 8.083_246_795_921_522;
const C62: f64 = -7.981_132_988_064_893;
const C63: f64 = -31.521_594_328_743_71;
const C64: f64 = 16.319_305_431_231_36;
const C65: f64 = -6.058_818_238_834_054;

// Dense output: y(θ) = (1 − θ)·y₀ + θ·(y₁ + (1 − θ)·(Σ H2ⱼuⱼ + θ·Σ H3ⱼuⱼ)).
const H21: f64 = 10.126_235_083_445_86;
const H22: f64 = -7.487_995_877_610_167;
const H23: f64 = -34.800_918_615_557_47;
const H24: f64 = -7.992_771_707_568_823;
const H25: f64 = 1.025_137_723_295_662;
const H31: f64 = -0.676_280_339_280_125_3;
const H32: f64 = 6.087_714_651_680_015;
const H33: f64 = 16.430_843_208_924_78;
const H34: f64 = 24.767_225_114_183_86;
const H35: f64 = -6.594_389_125_716_872;

/// Stage times cᵢ as fractions of the step (–), stages 1–6.
pub(super) const NODE: [f64; 6] = [0.0, C2, C3, C4, 1.0, 1.0];

/// ∂f/∂t weights h·dᵢ of each stage (as multiples of h; 0 for the last two).
pub(super) const TIME_RATE: [f64; 6] = [D1, D2, D3, D4, 0.0, 0.0];

/// Row i: the argument of stage i + 1 as y + Σⱼ ARGUMENT[i][j]·uⱼ₊₁; row 6 is y₁
/// (the last two stages add u₅, then u₆: stiffly accurate).
pub(super) const ARGUMENT: [[f64; 6]; 7] = [
    [0.0; 6],
    [A21, 0.0, 0.0, 0.0, 0.0, 0.0],
    [A31, A32, 0.0, 0.0, 0.0, 0.0],
    [A41, A42, A43, 0.0, 0.0, 0.0],
    [A51, A52, A53, A54, 0.0, 0.0],
    [A51, A52, A53, A54, 1.0, 0.0],
    [A51, A52, A53, A54, 1.0, 1.0],
];

/// Row i: the earlier stages' weights Cᵢⱼ (divided by h in use) in stage i + 1's
/// right-hand side.
pub(super) const MEMORY: [[f64; 5]; 6] = [
    [0.0; 5],
    [C21, 0.0, 0.0, 0.0, 0.0],
    [C31, C32, 0.0, 0.0, 0.0],
    [C41, C42, C43, 0.0, 0.0],
    [C51, C52, C53, C54, 0.0],
    [C61, C62, C63, C64, C65],
];

/// The two dense-output terms' weights on u₁ … u₅.
pub(super) const DENSE: [[f64; 5]; 2] = [[H21, H22, H23, H24, H25], [H31, H32, H33, H34, H35]];
