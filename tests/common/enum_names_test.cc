// One spelling table per enum (common/enum_names.h): printing, parsing, the refusal's words.
#include "common/enum_names.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace {

enum class Fruit { kApple, kPear, kPlum };
constexpr sortcell::EnumNames<Fruit, 3> kFruitNames{
    {{Fruit::kApple, "apple"}, {Fruit::kPear, "pear"}, {Fruit::kPlum, "plum"}}};
enum class Side { kLeft, kRight };
constexpr sortcell::EnumNames<Side, 2> kSideNames{{{Side::kLeft, "left"}, {Side::kRight, "right"}}};

TEST(EnumNames, EveryValueParsesBackFromItsName) {
  for (const auto& [value, name] : kFruitNames) {
    EXPECT_STREQ(sortcell::NameOf(kFruitNames, value), name);
    EXPECT_EQ(sortcell::ParseName(kFruitNames, name, "fruit"), value);
    EXPECT_EQ(sortcell::FindName(kFruitNames, name), value);
  }
  static_assert(sortcell::NameOf(kFruitNames, Fruit::kPear)[0] == 'p', "usable at compile time");
}

TEST(EnumNames, AnUnknownNameIsRefusedWithTheChoices) {
  EXPECT_FALSE(sortcell::FindName(kFruitNames, "Apple").has_value());
  try {
    sortcell::ParseName(kFruitNames, "kiwi", "fruit");
    FAIL() << "kiwi parsed";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "unknown fruit 'kiwi' (expected apple, pear or plum)");
  }
  EXPECT_EQ(sortcell::ExpectedNames(kSideNames), "left or right");
  EXPECT_EQ(sortcell::AllNames(kSideNames), (std::vector<std::string>{"left", "right"}));
}

TEST(EnumNames, AValueOutsideTheTableIsAQuestionMark) {
  EXPECT_STREQ(sortcell::NameOf(kSideNames, static_cast<Side>(7)), "?");
}

}  // namespace
