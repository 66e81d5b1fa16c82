#pragma once

#include "client/formats/score_builder.hpp"
#include "score/clef_xml.hpp"

// The clef every import fuzz target lands on: lra-phone as shipped, held in the program so a
// run reads no files.
namespace vibscore::fuzz {

inline const formats::ChosenClef& chosen_clef() {
    static const formats::ChosenClef chosen{"lra-phone",
                                            read_clef(R"(<VibClef type="sine" version="1.0">
  <Tempo>0.2</Tempo>
  <Numbers>
    <Number>0.2</Number><Number>0.3</Number><Number>0.4</Number><Number>0.5</Number>
    <Number>0.6</Number><Number>0.7</Number><Number>0.8</Number><Number>0.9</Number>
    <Number>1.0</Number>
  </Numbers>
  <Strings>
    <String>155</String><String>170</String><String>185</String>
    <String>200</String><String>215</String><String>235</String>
  </Strings>
</VibClef>)",
                                                      "lra-phone.clef.xml")};
    return chosen;
}

}  // namespace vibscore::fuzz
