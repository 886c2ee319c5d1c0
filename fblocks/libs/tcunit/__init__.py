"""TcUnit, TwinCAT's unit-test framework (tcunit.org, MIT), as a library of
softplc: the API its documentation gives (FB_TestSuite and its asserts,
TEST, TEST_ORDERED, TEST_FINISHED, TEST_FINISHED_NAMED, IS_TEST_FINISHED,
RUN, RUN_IN_SEQUENCE, GVL_Param_TcUnit, TCUNIT_ADSLOGSTR, WRITE_PROTECTED_*)
so that a TwinCAT project's own tests run under ``softplc test``, unchanged.
softplc's own implementation, not TcUnit's source:

    *.st         the API in ST: FB_TestSuite's assert methods compare as TcUnit
                 documents them and hand the result to natives
    natives.py   the native functions between the ST and the service
    service.py   the service the test runner binds: RUN, TEST, TEST_FINISHED,
                 the asserts, TcUnit's messages and results
    books.py     the suites, their tests and the asserts already reported
    values.py    values as TcUnit prints them; AssertEquals (ANY) and the
                 array asserts
"""
