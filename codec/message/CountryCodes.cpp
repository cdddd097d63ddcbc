#include "codec/message/CountryCodes.h"

#include <array>

namespace rcm {
namespace {

struct Country {
    char alpha2[3];
    std::uint16_t code;
    // Where several countries share a code, the one printed for it: the
    // "main country for code" of the ITU's and libphonenumber's listings.
    bool preferred = false;
};

// Sources: the ISO 3166-1 alpha-2 list (249 codes) and ITU-T E.164 Annex to
// ITU Operational Bulletin "List of ITU-T Recommendation E.164 assigned
// country codes", cross-checked against libphonenumber's
// CountryCodeToRegionCodeMap for the main country of a shared code.
// Left out, having no calling code of their own: BV (Bouvet Island), HM
// (Heard and McDonald Islands), UM (US Minor Outlying Islands). Territories
// served from another country's plan take that code: AQ 672 (Australian
// Antarctic Territory, 672 1), GS 500, PN 64, TF 262, VA 39 (379 is assigned
// but not in use). Kosovo (XK) is not an ISO code and is left out.
// Sorted by alpha-2: the static_asserts below hold it so.
constexpr Country kCountries[] = {
    {"AD", 376},       {"AE", 971},       {"AF", 93},        {"AG", 1},         {"AI", 1},
    {"AL", 355},       {"AM", 374},       {"AO", 244},       {"AQ", 672},       {"AR", 54},
    {"AS", 1},         {"AT", 43},        {"AU", 61, true},  {"AW", 297},       {"AX", 358},
    {"AZ", 994},       {"BA", 387},       {"BB", 1},         {"BD", 880},       {"BE", 32},
    {"BF", 226},       {"BG", 359},       {"BH", 973},       {"BI", 257},       {"BJ", 229},
    {"BL", 590},       {"BM", 1},         {"BN", 673},       {"BO", 591},       {"BQ", 599},
    {"BR", 55},        {"BS", 1},         {"BT", 975},       {"BW", 267},       {"BY", 375},
    {"BZ", 501},       {"CA", 1},         {"CC", 61},        {"CD", 243},       {"CF", 236},
    {"CG", 242},       {"CH", 41},        {"CI", 225},       {"CK", 682},       {"CL", 56},
    {"CM", 237},       {"CN", 86},        {"CO", 57},        {"CR", 506},       {"CU", 53},
    {"CV", 238},       {"CW", 599, true}, {"CX", 61},        {"CY", 357},       {"CZ", 420},
    {"DE", 49},        {"DJ", 253},       {"DK", 45},        {"DM", 1},         {"DO", 1},
    {"DZ", 213},       {"EC", 593},       {"EE", 372},       {"EG", 20},        {"EH", 212},
    {"ER", 291},       {"ES", 34},        {"ET", 251},       {"FI", 358, true}, {"FJ", 679},
    {"FK", 500, true}, {"FM", 691},       {"FO", 298},       {"FR", 33},        {"GA", 241},
    {"GB", 44, true},  {"GD", 1},         {"GE", 995},       {"GF", 594},       {"GG", 44},
    {"GH", 233},       {"GI", 350},       {"GL", 299},       {"GM", 220},       {"GN", 224},
    {"GP", 590, true}, {"GQ", 240},       {"GR", 30},        {"GS", 500},       {"GT", 502},
    {"GU", 1},         {"GW", 245},       {"GY", 592},       {"HK", 852},       {"HN", 504},
    {"HR", 385},       {"HT", 509},       {"HU", 36},        {"ID", 62},        {"IE", 353},
    {"IL", 972},       {"IM", 44},        {"IN", 91},        {"IO", 246},       {"IQ", 964},
    {"IR", 98},        {"IS", 354},       {"IT", 39, true},  {"JE", 44},        {"JM", 1},
    {"JO", 962},       {"JP", 81},        {"KE", 254},       {"KG", 996},       {"KH", 855},
    {"KI", 686},       {"KM", 269},       {"KN", 1},         {"KP", 850},       {"KR", 82},
    {"KW", 965},       {"KY", 1},         {"KZ", 7},         {"LA", 856},       {"LB", 961},
    {"LC", 1},         {"LI", 423},       {"LK", 94},        {"LR", 231},       {"LS", 266},
    {"LT", 370},       {"LU", 352},       {"LV", 371},       {"LY", 218},       {"MA", 212, true},
    {"MC", 377},       {"MD", 373},       {"ME", 382},       {"MF", 590},       {"MG", 261},
    {"MH", 692},       {"MK", 389},       {"ML", 223},       {"MM", 95},        {"MN", 976},
    {"MO", 853},       {"MP", 1},         {"MQ", 596},       {"MR", 222},       {"MS", 1},
    {"MT", 356},       {"MU", 230},       {"MV", 960},       {"MW", 265},       {"MX", 52},
    {"MY", 60},        {"MZ", 258},       {"NA", 264},       {"NC", 687},       {"NE", 227},
    {"NF", 672, true}, {"NG", 234},       {"NI", 505},       {"NL", 31},        {"NO", 47, true},
    {"NP", 977},       {"NR", 674},       {"NU", 683},       {"NZ", 64, true},  {"OM", 968},
    {"PA", 507},       {"PE", 51},        {"PF", 689},       {"PG", 675},       {"PH", 63},
    {"PK", 92},        {"PL", 48},        {"PM", 508},       {"PN", 64},        {"PR", 1},
    {"PS", 970},       {"PT", 351},       {"PW", 680},       {"PY", 595},       {"QA", 974},
    {"RE", 262, true}, {"RO", 40},        {"RS", 381},       {"RU", 7, true},   {"RW", 250},
    {"SA", 966},       {"SB", 677},       {"SC", 248},       {"SD", 249},       {"SE", 46},
    {"SG", 65},        {"SH", 290},       {"SI", 386},       {"SJ", 47},        {"SK", 421},
    {"SL", 232},       {"SM", 378},       {"SN", 221},       {"SO", 252},       {"SR", 597},
    {"SS", 211},       {"ST", 239},       {"SV", 503},       {"SX", 1},         {"SY", 963},
    {"SZ", 268},       {"TC", 1},         {"TD", 235},       {"TF", 262},       {"TG", 228},
    {"TH", 66},        {"TJ", 992},       {"TK", 690},       {"TL", 670},       {"TM", 993},
    {"TN", 216},       {"TO", 676},       {"TR", 90},        {"TT", 1},         {"TV", 688},
    {"TW", 886},       {"TZ", 255},       {"UA", 380},       {"UG", 256},       {"US", 1, true},
    {"UY", 598},       {"UZ", 998},       {"VA", 39},        {"VC", 1},         {"VE", 58},
    {"VG", 1},         {"VI", 1},         {"VN", 84},        {"VU", 678},       {"WF", 681},
    {"WS", 685},       {"YE", 967},       {"YT", 262},       {"ZA", 27},        {"ZM", 260},
    {"ZW", 263},
};

constexpr int kCountryCount = static_cast<int>(std::size(kCountries));
constexpr int kCodeLimit = 1000;  // E.164 country codes have at most 3 digits

constexpr int letterIndex(char a, char b) { return (a - 'A') * 26 + (b - 'A'); }

constexpr bool wellFormed()
{
    for (int i = 0; i < kCountryCount; ++i) {
        const Country& c = kCountries[i];
        if (c.alpha2[0] < 'A' || c.alpha2[0] > 'Z' || c.alpha2[1] < 'A' || c.alpha2[1] > 'Z' || c.alpha2[2] != 0)
            return false;
        if (c.code < 1 || c.code >= kCodeLimit)
            return false;
        if (i > 0 && letterIndex(kCountries[i - 1].alpha2[0], kCountries[i - 1].alpha2[1]) >=
                         letterIndex(c.alpha2[0], c.alpha2[1]))
            return false;  // unsorted or duplicated
    }
    return true;
}

// A shared code names exactly one preferred country; a code of its own needs
// no mark. Otherwise the printer's choice would be arbitrary.
constexpr bool onePreferredPerSharedCode()
{
    for (const Country& c : kCountries) {
        int sharing = 0, preferred = 0;
        for (const Country& d : kCountries) {
            if (d.code == c.code) {
                ++sharing;
                preferred += d.preferred ? 1 : 0;
            }
        }
        if (sharing > 1 ? preferred != 1 : preferred != 0)
            return false;
    }
    return true;
}

static_assert(wellFormed(), "kCountries: upper-case alpha-2, codes 1..999, sorted, no duplicates");
static_assert(onePreferredPerSharedCode(), "kCountries: each shared code needs exactly one preferred country");
static_assert(kCountryCount == 246, "249 ISO codes less BV, HM, UM");

// Both directions as direct-index tables, built at compile time: the printer
// looks a code up for every station of every frame.
constexpr auto kCodeByLetters = [] {
    std::array<std::uint16_t, 26 * 26> table{};
    for (const Country& c : kCountries)
        table[letterIndex(c.alpha2[0], c.alpha2[1])] = c.code;
    return table;
}();

constexpr auto kCountryByCode = [] {
    std::array<std::int16_t, kCodeLimit> table{};
    for (auto& entry : table)
        entry = -1;
    for (int i = 0; i < kCountryCount; ++i) {
        std::int16_t& entry = table[kCountries[i].code];
        if (entry < 0 || kCountries[i].preferred)
            entry = static_cast<std::int16_t>(i);
    }
    return table;
}();

constexpr char upper(char c) { return c >= 'a' && c <= 'z' ? static_cast<char>(c - 'a' + 'A') : c; }

}  // namespace

std::optional<std::uint16_t> diallingCodeForCountry(std::string_view alpha2)
{
    if (alpha2.size() != 2)
        return std::nullopt;
    const char a = upper(alpha2[0]), b = upper(alpha2[1]);
    if (a < 'A' || a > 'Z' || b < 'A' || b > 'Z')
        return std::nullopt;
    const std::uint16_t code = kCodeByLetters[letterIndex(a, b)];
    if (code == 0)
        return std::nullopt;
    return code;
}

std::string_view countryForDiallingCode(std::uint16_t code)
{
    if (code >= kCodeLimit || kCountryByCode[code] < 0)
        return {};
    return std::string_view(kCountries[kCountryByCode[code]].alpha2, 2);
}

}  // namespace rcm
