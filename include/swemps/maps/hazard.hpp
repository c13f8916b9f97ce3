#pragma once
// Flood hazard to people of one grid cell at one time, from the depth and the speed of the water
// there: the UK hazard rating HR and its four classes, and the Australian combined hazard classes
// H1-H6. Pure functions of two numbers; the maps of their maximum over a run are kept by
// FloodStatistics, which evaluates them on the depth and speed of the same sample (the hazard of
// the largest depth and the largest speed, reached at different times, would overstate it).
//
// UK hazard rating, HR = d (v + 0.5) + DF: d depth (m), v speed (m/s), DF a debris factor (-).
//   [TR1] HR Wallingford, Flood Hazard Research Centre (Middlesex University) and Risk & Policy
//         Analysts (2006). Flood Risks to People, Phase 2: The Flood Risks to People Methodology.
//         Defra / Environment Agency R&D Technical Report FD2321/TR1. Table 3.1 (debris factors),
//         the hazard-rating classes, Figure 3.2 (hazard of depth and speed).
//   [TR2] HR Wallingford et al. (2005). Framework and Guidance for Assessing and Managing Flood
//         Risk for New Development, Phase 2. Defra / Environment Agency R&D Technical Report
//         FD2320/TR2. Table 13.1 (hazard to people as a function of depth and velocity).
//   [Note] Defra / Environment Agency (2008). Supplementary note on flood hazard ratings and
//         thresholds for development planning and control purpose: clarification of the Table
//         13.1 of FD2320/TR2 and Figure 3.2 of FD2321/TR1. Table 1 repeats [TR1] Table 3.1.
//
// Debris factor, [TR1] Table 3.1 = [Note] Table 1 (the guidance table, by land use):
//     depth d                         pasture/arable  woodland  urban
//     0 to 0.25 m                          0             0        0
//     0.25 to 0.75 m                       0             0.5      1
//     d > 0.75 m and/or v > 2 m/s          0.5           1        1
// The last row is strict ("> 0.75", "> 2"), so 0.75 m and 2 m/s stay in the rows above; the
// shared end 0.25 m is read the same way, in the first row (the [Note] reads its own 0.25 m
// boundary as "less than and equal to"). Not implemented: the other published convention, that
// of [TR2] Table 13.1, which per the [Note] takes DF = 0.5 for d <= 0.25 m and 1.0 above
// whatever the land use - a screening simplification that gives still, ankle-deep water (and a
// dry cell) a rating of 0.5; LandUse::urban agrees with it above 0.25 m and is 0 below.
//
// Classes of HR ([TR1] hazard-rating classes; [Note]):
//     HR < 0.75          low          caution
//     0.75 to 1.25       moderate     danger for some (children, the elderly, the infirm)
//     1.25 to 2.0        significant  danger for most (the general public)
//     HR > 2.0           extreme      danger for all (the emergency services too)
// The source says "less than 0.75" and "more than 2.0", so HR = 0.75 is moderate and HR = 2.0
// significant. 1.25 ends one range and starts the next; we read the middle ranges as closed at
// the top like the last one, so HR = 1.25 is moderate. Some secondary sources quote 2.5 as the
// start of the extreme class, attributing it to [TR1]; we follow the [Note]: 2.0.
//
// Australian combined hazard classes ([AIDR] Table 2, the lowest class whose three limits all
// hold, each limit inclusive "<="; from [Smith] Tables 5-1 and 5-2, Figure 5-5):
//     class  depth d   speed v    d v         vulnerability ([AIDR] Table 1)
//     H1     <= 0.3 m  <= 2 m/s   <= 0.3 m2/s generally safe for vehicles, people and buildings
//     H2     <= 0.5    <= 2       <= 0.6      unsafe for small vehicles
//     H3     <= 1.2    <= 2       <= 0.6      unsafe for vehicles, children and the elderly
//     H4     <= 2.0    <= 2       <= 1.0      unsafe for vehicles and people
//     H5     <= 4.0    <= 4       <= 4.0      as H4; all buildings vulnerable to structural
//                                             damage, some less robust buildings to failure
//     H6     beyond H5 (depth, speed or d v)  as H4; all building types vulnerable to failure
//   [AIDR] Australian Institute for Disaster Resilience (2017). Flood Hazard. Australian
//          Disaster Resilience Guideline 7-3, supporting Handbook 7, Managing the Floodplain.
//          Table 1 (vulnerability thresholds), Table 2 (classification limits), combined hazard
//          curves figure.
//   [Smith] Smith, G. P., Davey, E. K. and Cox, R. J. (2014). Flood Hazard. Water Research
//          Laboratory Technical Report 2014/07, University of New South Wales.
// The speed limit alone can decide: shallow water at 2.5 m/s is H5, not H1.
//
// A dry cell, depth 0, has DF = 0, HR = 0 (low) and class H1 whatever the speed: there is no
// water to carry debris or to push, and the speed gridded where there is no water is noise.
// Films thinner than the run's wet depth should be screened out by the caller for the same
// reason (FloodStatistics does): a 1 mm film with a noisy 3 m/s would otherwise be H5.
// Inputs: depth and speed must be finite and >= 0 (speed is a magnitude), a rating finite and
// >= 0; anything else (NaN, infinite, negative) throws std::invalid_argument. Cells without
// data are the caller's to skip, not to classify.

#include <cstdint>
#include <string_view>

namespace swemps::maps {

// The dominant land use of a cell, which sets how much debris the water carries.
enum class LandUse : std::uint8_t { pasture_arable, woodland, urban };

// DF (-) of [TR1] Table 3.1 for this depth and speed on this land use.
double debris_factor(double depth_m, double speed_m_s, LandUse land);

// HR = d (v + 0.5) + DF (-).
double uk_hazard_rating(double depth_m, double speed_m_s, LandUse land);

// The values are those written to hazard-class maps.
enum class UkHazardClass : std::uint8_t { low = 1, moderate = 2, significant = 3, extreme = 4 };
UkHazardClass uk_hazard_class(double rating);

// The values are those written to hazard-class maps: H1 = 1 ... H6 = 6.
enum class AidrHazard : std::uint8_t { h1 = 1, h2 = 2, h3 = 3, h4 = 4, h5 = 5, h6 = 6 };
AidrHazard aidr_hazard(double depth_m, double speed_m_s);

// Short words for file metadata and legends, e.g. "H2: unsafe for small vehicles".
std::string_view name(LandUse land);
std::string_view name(UkHazardClass hazard);
std::string_view name(AidrHazard hazard);

}  // namespace swemps::maps
