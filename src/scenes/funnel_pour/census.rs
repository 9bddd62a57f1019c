//! Where the balls are: their places, the census of a step, and what a repeat records.

/// Where a ball is (see the [module doc](super)).
#[derive(
    Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, serde::Serialize, serde::Deserialize,
)]
pub enum Place {
    /// In the paste (centre in the cylinder, below the surface).
    Paste,
    /// Between the funnel and the paste.
    Falling,
    /// Still in the funnel.
    Funnel,
    /// Beside the cylinder, in the domain (escaped over the rim).
    Outside,
    /// Out of the domain, after escaping over the rim.
    Away,
    /// Through a wall, the funnel or the floor, or non-finite.
    Lost,
}

impl Place {
    /// CSV label.
    pub fn label(self) -> &'static str {
        match self {
            Self::Paste => "paste",
            Self::Falling => "falling",
            Self::Funnel => "funnel",
            Self::Outside => "outside",
            Self::Away => "away",
            Self::Lost => "lost",
        }
    }
}

/// Numbers of balls in each place.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct Census {
    /// In the paste.
    pub paste: usize,
    /// Falling between funnel and paste.
    pub falling: usize,
    /// In the funnel.
    pub funnel: usize,
    /// Beside the cylinder.
    pub outside: usize,
    /// Out of the domain (over the rim).
    pub away: usize,
    /// Through a wall or non-finite.
    pub lost: usize,
}

impl Census {
    /// Counts the places of the balls.
    pub fn of(places: impl IntoIterator<Item = Place>) -> Self {
        let mut c = Self::default();
        for p in places {
            match p {
                Place::Paste => c.paste += 1,
                Place::Falling => c.falling += 1,
                Place::Funnel => c.funnel += 1,
                Place::Outside => c.outside += 1,
                Place::Away => c.away += 1,
                Place::Lost => c.lost += 1,
            }
        }
        c
    }

    /// Balls in the domain (all but the away and lost ones).
    pub fn in_domain(&self) -> usize {
        self.paste + self.falling + self.funnel + self.outside
    }
}

/// One row of a repeat's time series.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Sample {
    /// Time since the outlet opened, s (negative while the balls settle in the funnel).
    pub time_s: f64,
    /// Where the balls are.
    pub census: Census,
    /// Largest ball speed, m/s.
    pub max_speed_m_s: f64,
}

/// One ball at the end of a repeat.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Ball {
    /// Diameter, m.
    pub diameter_m: f64,
    /// Centre (x, y, z), m; z above the cylinder bottom.
    pub position_m: [f64; 3],
    /// Speed, m/s.
    pub speed_m_s: f64,
    /// Where it is.
    pub place: Place,
}

/// Result of one repeat.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct RepeatResult {
    /// Repeat index (0-based).
    pub index: usize,
    /// Seed of the initial placement.
    pub seed: u64,
    /// The balls at the end.
    pub balls: Vec<Ball>,
    /// Where the balls were at `count_time_s` (None if the run ended before).
    pub census_at_count: Option<Census>,
    /// Largest ball speed when the outlet opened, m/s (how well they had settled).
    pub max_speed_at_opening_m_s: f64,
    /// Time since opening at which the run ended, s.
    pub end_time_s: f64,
    /// Steps taken (fill included).
    pub steps: u64,
    /// Wall time of this repeat, s.
    pub wall_time_s: f64,
    /// Time series (every `record.every_s`, default 0.01 s).
    pub samples: Vec<Sample>,
}

impl RepeatResult {
    /// Where the balls are at the end.
    pub fn census(&self) -> Census {
        Census::of(self.balls.iter().map(|b| b.place))
    }

    /// Lowest and highest centre height of the balls in the paste, m (None if none is).
    pub fn z_range_m(&self) -> Option<(f64, f64)> {
        z_range(self.balls.iter())
    }
}

/// Lowest and highest centre height of the balls in the paste among `balls`, m.
pub fn z_range<'a>(balls: impl Iterator<Item = &'a Ball>) -> Option<(f64, f64)> {
    balls
        .filter(|b| b.place == Place::Paste)
        .map(|b| b.position_m[2])
        .fold(None, |acc, z| match acc {
            None => Some((z, z)),
            Some((lo, hi)) => Some((lo.min(z), hi.max(z))),
        })
}
