#include "slam/reject/rejection_settings.h"

#include <set>

#include <gtest/gtest.h>

#include "common/testing/error_of.h"

namespace depot::slam {
namespace {

std::string apply(RejectionParams& p, const std::string& key, const std::string& value) {
  return error_of([&] { apply_rejection_setting(p, {key, value}, "here"); });
}

TEST(RejectionSettings, EveryKeyIsNamedOnceAndReachesItsOwnField) {
  std::set<std::string> keys;
  for (const RejectionSetting& s : rejection_settings()) {
    EXPECT_TRUE(keys.insert(s.key).second) << s.key << " twice";
    EXPECT_TRUE(s.in_full || s.in_masked) << s.key;
    EXPECT_STRNE(s.help, "") << s.key;
    // Setting one key changes exactly what its accessor reads back.
    RejectionParams p;
    switch (s.kind) {
      case RejectionSetting::Kind::kFlag: {
        const bool before = s.flag(p);
        EXPECT_EQ(apply(p, s.key, before ? "false" : "true"), "") << s.key;
        EXPECT_NE(s.flag(p), before) << s.key;
        break;
      }
      case RejectionSetting::Kind::kInteger:
        EXPECT_EQ(apply(p, s.key, std::to_string(static_cast<int>(s.hi))), "") << s.key;
        EXPECT_EQ(s.integer(p), static_cast<int>(s.hi)) << s.key;
        break;
      case RejectionSetting::Kind::kReal:
        EXPECT_EQ(apply(p, s.key, std::to_string(s.hi)), "") << s.key;
        EXPECT_FLOAT_EQ(s.real(p), static_cast<float>(s.hi)) << s.key;
        break;
      case RejectionSetting::Kind::kPersonMask:
        EXPECT_EQ(apply(p, s.key, "both"), "") << s.key;
        EXPECT_EQ(p.person_mask, RejectionParams::PersonMask::kBoth);
        break;
    }
  }
}

// What a setting's accessor reads, as text.
std::string value_of(const RejectionSetting& s, RejectionParams& p) {
  switch (s.kind) {
    case RejectionSetting::Kind::kFlag:
      return s.flag(p) ? "true" : "false";
    case RejectionSetting::Kind::kInteger:
      return std::to_string(s.integer(p));
    case RejectionSetting::Kind::kReal:
      return std::to_string(s.real(p));
    case RejectionSetting::Kind::kPersonMask:
      return std::to_string(static_cast<int>(p.person_mask));
  }
  return "";
}

TEST(RejectionSettings, NoTwoKeysShareAField) {
  // Each setting applied to fresh parameters leaves every other one as it was.
  for (const RejectionSetting& s : rejection_settings()) {
    RejectionParams defaults, changed;
    const std::string value =
        s.kind == RejectionSetting::Kind::kFlag         ? (s.flag(defaults) ? "false" : "true")
        : s.kind == RejectionSetting::Kind::kPersonMask ? "both"
        : s.kind == RejectionSetting::Kind::kInteger    ? std::to_string(static_cast<int>(s.hi))
                                                        : std::to_string(s.hi);
    ASSERT_EQ(apply(changed, s.key, value), "") << s.key;
    for (const RejectionSetting& t : rejection_settings()) {
      if (&t != &s) {
        EXPECT_EQ(value_of(t, changed), value_of(t, defaults)) << s.key << " moved " << t.key;
      }
    }
  }
}

TEST(RejectionSettings, BadValuesAreOneErrorNamingWhereTheyCameFrom) {
  RejectionParams p;
  EXPECT_EQ(apply(p, "mask.stride", "17"), "here: mask.stride must be in [1, 16] px");
  EXPECT_EQ(apply(p, "background_margin", "-1"), "here: background_margin must be in [0, 10] m");
  EXPECT_EQ(apply(p, "mask.extent", "0.001"), "here: mask.extent must be in [0.01, 10]");
  // The lower bound is the field's float: 0.01 is accepted.
  EXPECT_EQ(apply(p, "mask.extent", "0.01"), "");
  EXPECT_EQ(apply(p, "ego_flow", "perhaps"),
            "here: bad value 'perhaps' for rejection setting 'ego_flow'");
  const std::string unknown = apply(p, "mask.nonsense", "1");
  EXPECT_EQ(
      unknown.rfind(
          "here: unknown rejection setting 'mask.nonsense' (expected background_margin, ego_flow, ",
          0),
      0u)
      << unknown;
  EXPECT_NE(unknown.find(", ego.threshold)"), std::string::npos) << unknown;
}

TEST(RejectionSettings, ModesFollowWhatEachSettingActsOn) {
  // The depth split of boxes is full's; the object masks' keys masked's; the
  // flow test's extensions act in both; none acts in the paper's other modes.
  const auto acts = [](const char* key, RejectionMode m) {
    return find_rejection_setting(key)->acts_in(m);
  };
  EXPECT_TRUE(acts("background_margin", RejectionMode::kFull));
  EXPECT_FALSE(acts("background_margin", RejectionMode::kMasked));
  for (const char* key : {"mask.grow", "tracking.min_hits", "person_mask", "mask.plane"}) {
    EXPECT_FALSE(acts(key, RejectionMode::kFull)) << key;
    EXPECT_TRUE(acts(key, RejectionMode::kMasked)) << key;
  }
  for (const char* key :
       {"ego_flow", "test_static", "motion", "still.max_moving", "ego.threshold"}) {
    EXPECT_TRUE(acts(key, RejectionMode::kFull)) << key;
    EXPECT_TRUE(acts(key, RejectionMode::kMasked)) << key;
  }
  for (const RejectionSetting& s : rejection_settings())
    for (RejectionMode m : {RejectionMode::kOrb, RejectionMode::kOrbYolo, RejectionMode::kOrbLk})
      EXPECT_FALSE(s.acts_in(m)) << s.key;
  EXPECT_EQ(find_rejection_setting("nonsense"), nullptr);
}

}  // namespace
}  // namespace depot::slam
