// What the editor sends vibscored (client/editor/documents.*): each Clef href reduced to the file
// name the registry knows it by, and a document that reads back.
#include <gtest/gtest.h>

#include "client/editor/documents.hpp"
#include "score/document_error.hpp"
#include "score/score_xml.hpp"

namespace vibscore {
namespace {

Score score_with_href(const std::string& href) {
    return read_score("<VibScore version=\"1.0\"><Title>t</Title><Clef id=\"lra\" href=\"" + href +
                          "\"/><Bar clef=\"lra\"><Note length=\"quarter\" number=\"6\" "
                          "string=\"2\"/></Bar></VibScore>",
                      "t.score.xml")
        .score;
}

std::string registry_href(const std::string& href) {
    return read_score(editor::registry_document(score_with_href(href)), "registry.score.xml")
        .score.clefs.front()
        .href;
}

TEST(EditorDocuments, AClefHrefBecomesItsFileName) {
    EXPECT_EQ(registry_href("lra-phone.clef.xml"), "lra-phone.clef.xml");
    EXPECT_EQ(registry_href("../clefs/lra-phone.clef.xml"), "lra-phone.clef.xml");
    EXPECT_EQ(registry_href("/usr/share/vibscore/clefs/lra-phone.clef.xml"), "lra-phone.clef.xml");
}

TEST(EditorDocuments, AnHrefEndingInASlashStillNamesItsFileAndReadsBack) {
    // Found by the editor_file fuzzer: the file name of "x/" is empty, and a score with an empty
    // href does not read back.
    EXPECT_EQ(registry_href("lra-phone.clef.xml/"), "lra-phone.clef.xml");
    EXPECT_EQ(registry_href("clefs/lra-phone.clef.xml//"), "lra-phone.clef.xml");
}

TEST(EditorDocuments, AnHrefWithNoNameAtAllIsLeftForTheDaemonToRefuse) {
    EXPECT_EQ(registry_href("/"), "/");
    EXPECT_EQ(registry_href("///"), "///");
}

}  // namespace
}  // namespace vibscore
