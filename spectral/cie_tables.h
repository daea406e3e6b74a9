// Raw published CIE tables (see spectral/cie_tables.cpp for the sources). Use spectral/cie.h.
#pragma once

namespace iris::cie::tables {

constexpr int kCmfFirst = 360;   // nm
constexpr int kCmfLast = 830;    // nm
constexpr int kCmfCount = kCmfLast - kCmfFirst + 1;  // 1 nm spacing
constexpr int kD65First = 360;   // nm
constexpr int kD65Step = 5;      // nm
constexpr int kD65Count = (830 - 360) / kD65Step + 1;

extern const float kXBar[kCmfCount];
extern const float kYBar[kCmfCount];
extern const float kZBar[kCmfCount];
extern const float kD65[kD65Count];  // relative SPD, 100 at 560 nm

}  // namespace iris::cie::tables
